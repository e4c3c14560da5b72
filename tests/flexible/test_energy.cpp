// A free, undamped flexible model keeps T + V when it has no geometric
// stiffening (its elastic force is then -K eta, conservative). With
// geometric stiffening the motion-induced stiffness -K_G(omega, a) eta does
// work: the energy changes by exactly the integral of its power, which
// kanegen verify checks instead (power balance).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "flex_tip_body_linear.hpp"
#include "flexible_arm2.hpp"
#include "flexible_helpers.hpp"

namespace {

template <class System>
double energy_drift(const std::vector<double>& x, double t_end, double* e0_out) {
  const kanegen_test::EnergyDrift d = kanegen_test::energy_drift<System>(x, t_end, 20000000);
  INFO(d.result.message);
  REQUIRE(d.result.ok());
  *e0_out = d.initial_energy;
  return d.relative_drift;
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
