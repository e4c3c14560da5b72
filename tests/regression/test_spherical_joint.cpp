// SPDX-License-Identifier: GPL-2.0-or-later
// A heavy symmetric top on a spherical joint (tests/data/models/spherical_top.json)
// in steady precession, against the closed form. With the pivot's transverse
// inertia A = i1 + m l^2, the axial one C = i3, the tilt theta from the
// vertical, the spin psi_dot and the precession rate Omega about the
// vertical, the top precesses steadily when
//   m g l = Omega (C w3 - A Omega cos theta),   w3 = psi_dot + Omega cos theta
// (Goldstein, Classical Mechanics, the heavy symmetric top). Started on it
// (R = Rx(theta), angular velocity Omega (0, sin, cos) + psi_dot e_z in body
// axes), the axis R e_z must stay at (sin theta sin Omega t,
// -sin theta cos Omega t, cos theta): the joint's quaternion, its kinematic
// equation and the gyroscopic terms of the generated kernels are all in it.
// Integrated here by a classical Runge-Kutta of the test's own.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "spherical_top.hpp"

namespace {

using S = kanegen_models::spherical_top::System;

/// x = (q, u): q_dot from the kinematic equations, u_dot from the dynamics.
std::vector<double> rate(const S::Params& p, const std::vector<double>& x) {
  std::vector<double> dx(S::nq + S::nu);
  const double tau[S::nu] = {0, 0, 0};
  S::coordinate_rates(x.data(), x.data() + S::nq, dx.data());
  if (S::forward_dynamics(p, 0.0, x.data(), x.data() + S::nq, tau, dx.data() + S::nq) != 0)
    FAIL("M is not positive definite");
  return dx;
}

void rk4_step(const S::Params& p, std::vector<double>& x, double h) {
  const auto along = [&](const std::vector<double>& k, double s) {
    std::vector<double> y = x;
    for (std::size_t i = 0; i < y.size(); ++i) y[i] += s * k[i];
    return y;
  };
  const std::vector<double> k1 = rate(p, x), k2 = rate(p, along(k1, h / 2)), k3 = rate(p, along(k2, h / 2)),
                            k4 = rate(p, along(k3, h));
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

}  // namespace

TEST_CASE("spherical joint: a heavy symmetric top precesses steadily at the closed form's rate",
          "[spherical]") {
  REQUIRE(S::nq == 4);
  REQUIRE(S::nu == 3);
  const S::Params p{};
  const double m = 1.0, l = 0.5, i1 = 0.05, i3 = 0.1, g = 9.81;  // the model file's
  const double A = i1 + m * l * l, C = i3;
  const double theta = GENERATE(0.3, 1.2), spin = 40.0;
  // (C - A) cos(theta) Omega^2 + C spin Omega - m g l = 0: the slow root.
  const double a = (C - A) * std::cos(theta), b = C * spin, c = -m * g * l;
  const double omega = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
  INFO("theta = " << theta << ", precession " << omega << " rad/s");
  REQUIRE(omega > 0);
  REQUIRE(std::abs(m * g * l - omega * (C * (spin + omega * std::cos(theta)) - A * omega * std::cos(theta))) <
          1e-12);

  // q: x, y, z, then w; R = Rx(theta).
  std::vector<double> x{std::sin(theta / 2),           0, 0, std::cos(theta / 2), 0, omega * std::sin(theta),
                        omega * std::cos(theta) + spin};
  const double energy0 = S::kinetic_energy(p, x.data(), x.data() + S::nq) + S::potential_energy(p, x.data());
  const double h = 1e-4, t_end = 2.0;
  double worst_axis = 0, worst_energy = 0;
  std::array<double, 3> axis{};
  for (int k = 1; k <= static_cast<int>(t_end / h + 0.5); ++k) {
    rk4_step(p, x, h);
    if (k % 1000 != 0) continue;
    const double t = k * h;
    std::array<double, 3> y{};
    S::outputs(p, t, x.data(), x.data() + S::nq, y.data());  // the point at 1 on the axis
    axis = {std::sin(theta) * std::sin(omega * t), -std::sin(theta) * std::cos(omega * t), std::cos(theta)};
    for (int i = 0; i < 3; ++i) worst_axis = std::max(worst_axis, std::abs(y[i] - axis[i]));
    const double energy = S::kinetic_energy(p, x.data(), x.data() + S::nq) + S::potential_energy(p, x.data());
    worst_energy = std::max(worst_energy, std::abs(energy - energy0) / energy0);
  }
  const double length = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3]);
  std::printf(
      "top at tilt %.1f: precession %.6f rad/s; axis off by %.1e, energy by %.1e (relative), |q| - 1 = "
      "%.1e\n",
      theta, omega, worst_axis, worst_energy, length - 1);
  CHECK(worst_axis < 1e-8);
  CHECK(worst_energy < 1e-10);
  CHECK(std::abs(length - 1) < 1e-10);  // the kinematic equation keeps the quaternion's length
  CHECK(omega * t_end > 0.5);           // it has precessed by a visible angle
}
