// SPDX-License-Identifier: GPL-2.0-or-later
// A prismatic and a revolute joint, a joint spring and damper, inputs, and
// constant point forces in world and body axes, against the closed form from
// Lagrange's equations. Cart position x, pendulum angle q about +y (q = 0
// hangs down), bob at (x - l sin q, 0, -l cos q):
//   M = [[m_cart + m, -m l cos q], [-m l cos q, m l^2]]
//   f_x = -m l sin q qd^2 + fx + b cos q + tau_x
//   f_q = -m g l sin q - fx l cos q + fz l sin q - b l - k (q - rest) - c qd + tau_q
//   V   = -m g l cos q + k (q - rest)^2 / 2 + fx l sin q + fz l cos q - fx x
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "forced_cart_pendulum.hpp"

TEST_CASE("cart pendulum with springs, dampers, inputs and point forces matches the closed form",
          "[regression][forces]") {
  namespace model = kanegen_models::forced_cart_pendulum;
  model::Params p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(-3.0, 3.0);
  for (int sample = 0; sample < 20; ++sample) {
    const double q[2] = {any(rng), any(rng)}, u[2] = {any(rng), any(rng)}, tau[2] = {any(rng), any(rng)};
    const double s = std::sin(q[1]), c = std::cos(q[1]), qd = u[1];
    double m[4], f[2], y[3];
    model::mass_matrix(p, q, m);
    model::forcing(p, 0.0, q, u, tau, f);
    model::outputs(p, 0.0, q, u, y);
    INFO("sample " << sample);
    CHECK(m[0] == Approx(p.m_cart + p.m).epsilon(1e-13));
    CHECK(m[1] == Approx(-p.m * p.l * c).margin(1e-13));
    CHECK(m[2] == Approx(-p.m * p.l * c).margin(1e-13));
    CHECK(m[3] == Approx(p.m * p.l * p.l).epsilon(1e-13));
    CHECK(f[0] == Approx(-p.m * p.l * s * qd * qd + p.fx + p.b * c + tau[0]).margin(1e-12));
    CHECK(f[1] == Approx(-p.m * p.g * p.l * s - p.fx * p.l * c + p.fz * p.l * s - p.b * p.l -
                         p.k * (q[1] - p.rest) - p.c * qd + tau[1])
                      .margin(1e-12));
    CHECK(model::potential_energy(p, q) ==
          Approx(-p.m * p.g * p.l * c + 0.5 * p.k * (q[1] - p.rest) * (q[1] - p.rest) + p.fx * p.l * s +
                 p.fz * p.l * c - p.fx * q[0])
              .margin(1e-12));
    const double vx = u[0] - p.l * c * qd, vz = p.l * s * qd;
    CHECK(model::kinetic_energy(p, q, u) ==
          Approx(0.5 * p.m_cart * u[0] * u[0] + 0.5 * p.m * (vx * vx + vz * vz)).margin(1e-12));
    CHECK(y[0] == Approx(q[0] - p.l * s).margin(1e-14));
    CHECK(y[1] == Approx(0.0).margin(1e-14));
    CHECK(y[2] == Approx(-p.l * c).margin(1e-14));
  }
}
