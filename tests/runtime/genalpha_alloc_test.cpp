// SPDX-License-Identifier: GPL-2.0-or-later
// GenAlpha::start and step allocate nothing, and neither does a step of the
// Radau integrator: the global operator new of this test executable counts
// its calls while the counter is armed.
#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

#include "genalpha_models.hpp"
#include "kanegen/runtime/genalpha.hpp"
#include "kanegen/runtime/integrators.hpp"

namespace {
std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};
}  // namespace

void* operator new(std::size_t size) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace kanegen::runtime;

namespace {

/// Allocations during a start and `steps` steps of `table` from its initial state.
long allocations_in_steps(const ModelTable& table, bool reuse, int steps) {
  Model model(table);
  GenAlphaOptions o;
  o.h = 1e-3;
  o.reuse_jacobian = reuse;
  GenAlpha ga(model, o);
  double q[2], u[2];
  model.initial_state(q, u);
  std::string why;
  REQUIRE(ga.start(0.0, q, u, nullptr, &why));
  g_allocations = 0;
  g_counting = true;
  bool ok = ga.start(0.0, q, u, nullptr, &why);  // a restart allocates nothing either
  for (int i = 0; i < steps && ok; ++i) ok = ga.step(nullptr, &why);
  g_counting = false;
  REQUIRE(ok);
  REQUIRE(ga.stats().steps == steps);
  return g_allocations;
}

}  // namespace

TEST_CASE("genalpha: start() and step() allocate nothing", "[genalpha]") {
  using namespace genalpha_models;
  // The counter works: a string that outgrows its small buffer allocates.
  g_allocations = 0;
  g_counting = true;
  std::string s(100, 'x');
  g_counting = false;
  REQUIRE(g_allocations >= 1);

  for (bool reuse : {true, false}) {
    INFO("reuse_jacobian " << reuse);
    CHECK(allocations_in_steps(chain_table(), reuse, 500) == 0);
    CHECK(allocations_in_steps(point_pendulum_table(), reuse, 500) == 0);     // loops, speed correction
    CHECK(allocations_in_steps(cart_pendulum_table(true), reuse, 500) == 0);  // prescribed coordinate
  }
}

namespace {

/// Allocations and steps of a Radau run to t_end of a stiff, nonlinear
/// oscillator (q' = u, u' = -k sin q - c u): its Newton iterations, its
/// rejected steps and its dense output to the rows.
std::pair<long, long> radau_allocations(double t_end) {
  constexpr double k = 1e4, c = 0.5;
  const Rhs rhs = [](double, const double* x, double* xdot) {
    xdot[0] = x[1];
    xdot[1] = -k * std::sin(x[0]) - c * x[1];
    return true;
  };
  const Jacobian jac = [](double, const double* x, double* J) {
    J[0] = 0.0, J[1] = 1.0, J[2] = -k * std::cos(x[0]), J[3] = -c;
    return true;
  };
  const Observer observer = [](double, const double*) { return true; };
  IntegrationOptions o;
  o.t_end = t_end;
  o.dt = 0.01;
  o.rtol = 1e-6;
  o.atol = 1e-8;
  double x[2] = {1.0, 0.0};
  g_allocations = 0;
  g_counting = true;
  const IntegrationResult r = integrate(Method::kRadau, rhs, 0.0, x, 2, o, observer, jac);
  g_counting = false;
  REQUIRE(r.ok());
  return {g_allocations.load(), r.stats.accepted + r.stats.rejected};
}

}  // namespace

TEST_CASE("radau: its steps allocate nothing", "[implicit]") {
  // The workspace is sized once per run: as many allocations for a run of
  // hundreds of steps as for one of a few.
  const auto [few, few_steps] = radau_allocations(0.01);
  const auto [many, many_steps] = radau_allocations(2.0);
  INFO(few_steps << " and " << many_steps << " steps");
  CHECK(many_steps > 20 * few_steps);
  CHECK(many == few);
}
