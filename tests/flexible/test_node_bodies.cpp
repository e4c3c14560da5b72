// SPDX-License-Identifier: GPL-2.0-or-later
// A rigid body on a beam's tip node (a fixed joint with parent_node) must
// give the same equations as the same mass and inertia given to the beam as
// its tip mass (flexible.tip): two independent routes, one through the
// node's kinematics and one through the finite-element mass points. With
// geometric stiffening or without, they agree to round-off.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "flex_tip_body.hpp"
#include "flex_tip_body_linear.hpp"
#include "flex_tip_mass.hpp"
#include "flex_tip_mass_linear.hpp"

namespace {

struct Largest {
  double mass = 0, forcing = 0, energy = 0;
};

template <class A, class B>
Largest compare(int samples) {
  static_assert(A::nq == B::nq && A::nu == B::nu, "twins");
  constexpr int n = A::nu;
  typename A::Params pa;
  typename B::Params pb;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> hub(-3, 3), elastic(-0.02, 0.02), rate(-3, 3), elastic_rate(-0.2, 0.2);
  Largest out;
  for (int s = 0; s < samples; ++s) {
    double q[n], u[n], tau[n] = {}, ma[n * n], mb[n * n], fa[n], fb[n];
    q[0] = hub(rng);
    u[0] = rate(rng);
    for (int i = 1; i < n; ++i) {
      q[i] = elastic(rng);
      u[i] = elastic_rate(rng);
    }
    A::mass_matrix(pa, q, ma);
    B::mass_matrix(pb, q, mb);
    A::forcing(pa, 0.0, q, u, tau, fa);
    B::forcing(pb, 0.0, q, u, tau, fb);
    double m_scale = 0, f_scale = 0, dm = 0, df = 0;
    for (int i = 0; i < n * n; ++i) {
      m_scale = std::max(m_scale, std::abs(ma[i]));
      dm = std::max(dm, std::abs(ma[i] - mb[i]));
    }
    for (int i = 0; i < n; ++i) {
      f_scale = std::max(f_scale, std::abs(fa[i]));
      df = std::max(df, std::abs(fa[i] - fb[i]));
    }
    const double ea = A::kinetic_energy(pa, q, u) + A::potential_energy(pa, q);
    const double eb = B::kinetic_energy(pb, q, u) + B::potential_energy(pb, q);
    out.mass = std::max(out.mass, dm / m_scale);
    out.forcing = std::max(out.forcing, df / f_scale);
    out.energy = std::max(out.energy, std::abs(ea - eb) / std::abs(ea));
  }
  return out;
}

}  // namespace

TEST_CASE("a body on the tip node equals the beam's tip mass (linear beam)", "[flexible][node]") {
  const Largest d = compare<kanegen_models::flex_tip_mass_linear::System, kanegen_models::flex_tip_body_linear::System>(50);
  INFO("largest relative differences: M " << d.mass << ", f " << d.forcing << ", T + V " << d.energy);
  CHECK(d.mass < 1e-13);
  CHECK(d.forcing < 1e-12);
  CHECK(d.energy < 1e-13);
}

TEST_CASE("a body on the tip node stiffens the beam as its tip mass does", "[flexible][node]") {
  // Geometric stiffening of a nodal beam is its nonlinear axial strain: the
  // body's pull stretches the beam through the node's axial coordinate, as
  // the tip mass's does, so the two models agree to round-off (the old
  // motion-induced stiffness loaded them differently, at second order).
  const Largest d = compare<kanegen_models::flex_tip_mass::System, kanegen_models::flex_tip_body::System>(50);
  INFO("largest relative differences: M " << d.mass << ", f " << d.forcing << ", T + V " << d.energy);
  CHECK(d.mass < 1e-13);
  CHECK(d.energy < 1e-13);
  CHECK(d.forcing < 1e-12);
}
