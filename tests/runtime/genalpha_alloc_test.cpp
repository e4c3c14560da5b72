// SPDX-License-Identifier: GPL-2.0-or-later
// GenAlpha::start and step allocate nothing: the global operator new of this test
// executable counts its calls while the counter is armed.
#include <atomic>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <new>
#include <string>

#include "genalpha_models.hpp"
#include "kanegen/runtime/genalpha.hpp"

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
