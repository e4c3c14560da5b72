// SPDX-License-Identifier: GPL-2.0-or-later
// Geometric stiffness from axial loads: the rotating cantilever against the
// published table (formulation.md, Hamza-Cherif & Houmat 2004), the in-plane
// spin softening, and buckling under a tip force (Euler) and under a uniform
// axial load (Greenhill's standing column) as checks of K_G's distributions.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "fem/invariants.hpp"
#include "fem/rotating.hpp"
#include "fem_test_support.hpp"

using namespace kanegen::fem;
using fem_test::rel_error;

namespace {

constexpr double kLength = 1.5;

struct TableRow {
  double lambda, omega[3];
};
// Nondimensional flapwise frequencies omega sqrt(rho A L^4 / E I), hub radius 0.
const TableRow kTable[] = {{0.0, {3.5160, 22.0345, 61.6973}},
                           {2.0, {4.1373, 22.6149, 62.2732}},
                           {4.0, {5.5850, 24.2734, 63.9668}},
                           {10.0, {11.2023, 33.6404, 74.6494}}};

const std::vector<DofKind> kV = {DofKind::kUy, DofKind::kRz}, kW = {DofKind::kUz, DofKind::kRy};

/// The first three nondimensional frequencies of the modes in `kinds` for spin `omega_dir * Omega`.
std::vector<double> rotating(const Body& body, double EI, double rho_a, double lambda,
                             const Eigen::Vector3d& axis, const std::vector<DofKind>& kinds, bool softening) {
  const double scale = std::sqrt(EI / (rho_a * std::pow(kLength, 4)));
  const Eigen::MatrixXd K = rotating_stiffness(body, lambda * scale * axis, softening);
  const auto omega =
      fem_test::frequencies_of(body, support_constraint(body, Support::kClamped), body.mass(), K, kinds);
  return {omega[0] / scale, omega[1] / scale, omega[2] / scale};
}

/// The compressive load factor f at which K_e - f K_G turns singular on the constrained dofs
/// (K_G for a unit tension load).
double critical_factor(const Body& body, const Eigen::MatrixXd& kg) {
  const Constraint c = support_constraint(body, Support::kClamped);
  // K_G is only semidefinite (no axial terms); solve K_G x = mu K_e x and take f = 1 / mu_max.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(c.reduce(kg), c.reduce(body.stiffness()));
  return 1.0 / solver.eigenvalues().maxCoeff();
}

}  // namespace

TEST_CASE("rotating: centrifugal axial force is rho A Omega^2 (L^2 - x^2) / 2, plus tip masses",
          "[rotating]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const double rho_a = p.material.rho * p.section.A, w2 = 9.0, start = 0.25, tip_mass = 0.3;
  Body body = make_beam_chain(p, kLength, 4, start);
  const auto force = chain_axial_force(body, 0.0, w2);
  const double tip = start + kLength, h = kLength / 4;
  for (int e = 0; e < 4; ++e)
    for (double xi : {0.0, 0.3, 0.999}) {
      const double x = start + (e + xi) * h;
      CHECK(force(e).axial_force(xi) == Approx(rho_a * w2 * (tip * tip - x * x) / 2.0));
    }
  body.add_point_mass(body.num_nodes() - 1, tip_mass);
  const auto with_mass = chain_axial_force(body, -2.0, w2, 5.0);
  const double x = start + 0.5 * h;
  CHECK(with_mass(0).axial_force(0.5) ==
        Approx(5.0 + rho_a * (-2.0 * (tip - x) + w2 * (tip * tip - x * x) / 2.0) +
               tip_mass * (-2.0 + w2 * tip)));
}

TEST_CASE("rotating: flapwise frequencies within 0.5 % of the table at lambda = 0, 2, 4, 10", "[rotating]") {
  // Planar body spun about y: its v bending is out of the plane of rotation (x-z).
  const BeamProperties planar = fem_test::steel_beam(BeamKind::kPlanar);
  const Body pb = make_beam_chain(planar, kLength, 10);
  // Spatial body spun about z: flapwise is w, with E Iy.
  const BeamProperties spatial = fem_test::steel_beam(BeamKind::kSpatial);
  const Body sb = make_beam_chain(spatial, kLength, 10);
  const double rho_a = planar.material.rho * planar.section.A, E = planar.material.E;
  for (const TableRow& row : kTable) {
    const auto flap_planar =
        rotating(pb, E * planar.section.Iz, rho_a, row.lambda, Eigen::Vector3d::UnitY(), kV, true);
    const auto flap_spatial =
        rotating(sb, E * spatial.section.Iy, rho_a, row.lambda, Eigen::Vector3d::UnitZ(), kW, true);
    for (int n = 0; n < 3; ++n) {
      INFO("lambda " << row.lambda << " mode " << n + 1 << ": planar " << flap_planar[n] << ", spatial "
                     << flap_spatial[n] << ", table " << row.omega[n]);
      CHECK(std::abs(rel_error(flap_planar[n], row.omega[n])) < 5e-3);
      CHECK(std::abs(rel_error(flap_spatial[n], row.omega[n])) < 5e-3);
    }
  }
}

TEST_CASE("rotating: in-plane frequencies satisfy omega^2 = omega_flap^2 - Omega^2", "[rotating]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const Body body = make_beam_chain(p, kLength, 10);
  const double rho_a = p.material.rho * p.section.A, EI = p.material.E * p.section.Iz;
  for (const TableRow& row : kTable) {
    const auto flap = rotating(body, EI, rho_a, row.lambda, Eigen::Vector3d::UnitY(), kV, true);
    const auto in_plane = rotating(body, EI, rho_a, row.lambda, Eigen::Vector3d::UnitZ(), kV, true);
    const auto unsoftened = rotating(body, EI, rho_a, row.lambda, Eigen::Vector3d::UnitZ(), kV, false);
    for (int n = 0; n < 3; ++n) {
      INFO("lambda " << row.lambda << " mode " << n + 1);
      const double lambda2 = row.lambda * row.lambda;
      CHECK(in_plane[n] * in_plane[n] == Approx(flap[n] * flap[n] - lambda2).epsilon(1e-9));
      CHECK(unsoftened[n] == Approx(flap[n]).epsilon(1e-9));
      CHECK(std::abs(rel_error(in_plane[n], std::sqrt(row.omega[n] * row.omega[n] - lambda2))) < 5e-3);
    }
  }
}

TEST_CASE("rotating: the stiffening is Omega^2 times one matrix, and it is what lifts the frequencies",
          "[rotating]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  const Body body = make_beam_chain(p, kLength, 6);
  const GeometricStiffnessBasis basis = geometric_stiffness_basis(body);
  const double omega = 7.0;
  const Eigen::MatrixXd k = rotating_stiffness(body, Eigen::Vector3d(0.0, 0.0, omega), false);
  CHECK((k - body.stiffness() - omega * omega * basis.linear).norm() < 1e-12 * k.norm());
  // The spin about the beam's own axis loads nothing axially.
  const Eigen::MatrixXd k_axis = rotating_stiffness(body, Eigen::Vector3d(omega, 0.0, 0.0), false);
  CHECK((k_axis - body.stiffness()).norm() == 0.0);
  // Without K_G (the linear model) the in-plane frequency drops with the spin and vanishes at
  // Omega = omega_1: the divergence of the spin-up beam.
  const double rho_a = p.material.rho * p.section.A, EI = p.material.E * p.section.Iz;
  const double w1 = fem_test::bending_omega(fem_test::cantilever_beta_l(0), EI, rho_a, kLength);
  const InertiaInvariants inv = body_invariants(body);
  const Eigen::Vector3d spin(0.0, 0.0, 1.01 * w1);
  const Eigen::MatrixXd linear_model = body.stiffness() + spin_softening(inv, spin);
  const Constraint c = support_constraint(body, Support::kClamped);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(c.reduce(linear_model),
                                                                   c.reduce(body.mass()));
  CHECK(solver.eigenvalues()[0] < 0.0);
  CHECK(fem_test::frequencies(c, body.mass(), rotating_stiffness(body, spin, true))[0] > 0.5 * w1);
}

TEST_CASE("rotating: Euler buckling of a cantilever under a tip force, pi^2 E I / (4 L^2)", "[rotating]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const Body body = make_beam_chain(p, kLength, 10);
  const double EI = p.material.E * p.section.Iz;
  const double p_cr = critical_factor(body, geometric_stiffness_basis(body).tip);
  CHECK(std::abs(rel_error(p_cr, M_PI * M_PI * EI / (4.0 * kLength * kLength))) < 1e-4);
}

TEST_CASE("rotating: a standing column buckles under its own weight at q L^3 / (E I) = 7.8373",
          "[rotating]") {
  // Greenhill: the first root of J_{-1/3}(2/3 sqrt(q L^3 / E I)) = 0 gives q L^3 / E I = 7.837347.
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const Body body = make_beam_chain(p, kLength, 10);
  const double EI = p.material.E * p.section.Iz, rho_a = p.material.rho * p.section.A;
  const double g_cr = critical_factor(body, geometric_stiffness_basis(body).uniform);
  CHECK(std::abs(rel_error(rho_a * g_cr * std::pow(kLength, 3) / EI, 7.837347)) < 1e-3);
}
