// SPDX-License-Identifier: GPL-2.0-or-later
// The force elements of a model file against closed forms: a spring to the
// ground makes a slider oscillate at sqrt(k/m) (damped with a damper), a
// pendulum with springs keeps T + V, and a constant joint effort spins a
// rotor up at tau/J. Each is a simulation of the generated kernels.
#include <catch2/catch.hpp>
#include <cmath>
#include <kanegen/runtime/integrators.hpp>
#include <vector>

#include "effort_rotor.hpp"
#include "spring_oscillator.hpp"
#include "spring_pendulum.hpp"
#include "system_helpers.hpp"

namespace {

using kanegen::runtime::IntegrationOptions;
using kanegen::runtime::Method;

/// Integrates System from its initial state to t_end (DOPRI5, rtol 1e-11),
/// calling `check(t, x)` at every output (dt 0.01).
template <class System, class Check>
void simulate(const typename System::Params& p, double t_end, Check&& check) {
  std::vector<double> x(System::nq + System::nu);
  System::initial_state(p, x.data(), x.data() + System::nq);
  IntegrationOptions opt;
  opt.t_end = t_end;
  opt.dt = 0.01;
  opt.rtol = 1e-11;
  opt.atol = 1e-13;
  opt.max_steps = 1000000;
  const auto result =
      kanegen::runtime::integrate(Method::kDopri5, kanegen_test::rhs<System>(p), 0.0, x.data(),
                                  static_cast<int>(x.size()), opt, [&](double t, const double* state) {
                                    check(t, state);
                                    return true;
                                  });
  REQUIRE(result.ok());
}

}  // namespace

TEST_CASE("a slider on a spring to the ground oscillates at sqrt(k/m)", "[regression][spring]") {
  using System = kanegen_models::spring_oscillator::System;
  System::Params p;  // m = 2, k = 50: omega = 5 rad/s; x0 = 0.1 m, at rest
  const double omega = std::sqrt(p.k / p.m), x0 = 0.1;
  double worst = 0;
  simulate<System>(p, 10.0, [&](double t, const double* x) {
    worst = std::max(worst, std::abs(x[0] - x0 * std::cos(omega * t)));
  });
  INFO("undamped: max |x - x0 cos(omega t)| over 10 s (8 periods) = " << worst);
  CHECK(worst < 1e-8);

  // With a damper, zeta = c / (2 sqrt(k m)) = 0.1.
  p.c = 2.0;
  const double zeta = p.c / (2 * std::sqrt(p.k * p.m)), omega_d = omega * std::sqrt(1 - zeta * zeta);
  worst = 0;
  simulate<System>(p, 10.0, [&](double t, const double* x) {
    const double exact = x0 * std::exp(-zeta * omega * t) *
                         (std::cos(omega_d * t) + zeta * omega / omega_d * std::sin(omega_d * t));
    worst = std::max(worst, std::abs(x[0] - exact));
  });
  INFO("damped (zeta 0.1): max |x - x_exact| = " << worst);
  CHECK(worst < 1e-8);

  // The spring's potential energy k (l - l0)^2 / 2, l = x + L, l0 = L.
  const double q[1] = {0.3};
  CHECK(System::potential_energy(p, q) == Approx(0.5 * p.k * 0.3 * 0.3).epsilon(1e-14));
}

TEST_CASE("a double pendulum with springs to the ground and between its links keeps T + V",
          "[regression][spring]") {
  using System = kanegen_models::spring_pendulum::System;
  std::vector<double> x0(System::nq + System::nu);
  System::Params p;
  System::initial_state(p, x0.data(), x0.data() + System::nq);
  const kanegen_test::EnergyDrift d = kanegen_test::energy_drift<System>(x0, 10.0, 2000000);
  REQUIRE(d.result.ok());
  INFO("E0 = " << d.initial_energy << ", relative drift over 10 s = " << d.relative_drift);
  CHECK(std::abs(d.initial_energy) > 1.0);
  CHECK(d.relative_drift < 1e-8);
}

TEST_CASE("a constant joint effort spins a rotor up at tau/J", "[regression][effort]") {
  using System = kanegen_models::effort_rotor::System;
  System::Params p;  // J = 0.5, tau0 = 2: alpha = 4 rad/s^2
  const double alpha = p.tau0 / p.J;
  const double q[1] = {0.7}, u[1] = {3.0}, tau[1] = {0.0};
  double udot[1];
  REQUIRE(System::forward_dynamics(p, 0.0, q, u, tau, udot) == 0);
  CHECK(udot[0] == Approx(alpha).epsilon(1e-14));
  double worst_q = 0, worst_u = 0;
  simulate<System>(p, 5.0, [&](double t, const double* x) {
    worst_q = std::max(worst_q, std::abs(x[0] - alpha * t * t / 2));
    worst_u = std::max(worst_u, std::abs(x[1] - alpha * t));
  });
  INFO("max |q - alpha t^2/2| = " << worst_q << ", max |u - alpha t| = " << worst_u << " over 5 s");
  CHECK(worst_q < 1e-9);
  CHECK(worst_u < 1e-9);
}
