// A free, undamped flexible model keeps T + V when it has no geometric
// stiffening (its elastic force is then -K eta, conservative). With
// geometric stiffening the motion-induced stiffness -K_G(omega, a) eta does
// work: the energy changes by exactly the integral of its power, which is
// checked instead (power balance).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "flex_tip_body_linear.hpp"
#include "flexible_arm2.hpp"
#include "flexible_helpers.hpp"

namespace {

template <class System>
double energy_drift(std::vector<double> x, double t_end, double* e0_out) {
  typename System::Params p;
  const double e0 = kanegen_test::energy<System>(p, x.data());
  double worst = 0.0;
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = 0.01;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.max_steps = 20000000;
  const auto result = kanegen::runtime::integrate(
      kanegen::runtime::Method::kDopri5, kanegen_test::rhs<System>(p), 0.0, x.data(), static_cast<int>(x.size()),
      opt, [&](double, const double* state) {
        worst = std::max(worst, std::abs(kanegen_test::energy<System>(p, state) - e0));
        return true;
      });
  INFO(result.message);
  REQUIRE(result.ok());
  *e0_out = e0;
  return worst / std::abs(e0);
}

template <class System>
std::vector<double> initial_state() {
  std::vector<double> x(System::q0(), System::q0() + System::nq);
  x.insert(x.end(), System::u0(), System::u0() + System::nu);
  return x;
}

}  // namespace

TEST_CASE("a free flexible pendulum without stiffening conserves energy", "[flexible][energy]") {
  using System = kanegen_models::flex_tip_body_linear::System;
  std::vector<double> x = initial_state<System>();
  x[0] = 0.3;                // hub angle: swinging in gravity
  x[System::nq] = 1.0;       // hub rate
  x[System::nq + 2] = 0.05;  // some bending velocity
  double e0 = 0;
  const double drift = energy_drift<System>(x, 5.0, &e0);
  INFO("E0 = " << e0 << ", relative drift " << drift);
  CHECK(drift < 1e-8);
}

TEST_CASE("the free two-link flexible arm conserves energy", "[flexible][energy]") {
  using System = kanegen_models::flexible_arm2::System;
  double e0 = 0;
  const double drift = energy_drift<System>(initial_state<System>(), 3.0, &e0);
  INFO("E0 = " << e0 << ", relative drift " << drift);
  CHECK(drift < 1e-8);
}
