// SPDX-License-Identifier: GPL-2.0-or-later
// One beam element: rigid motions, the closed-form matrices against their
// quadrature, hand-computed energies, and the dof sign conventions.
#include <catch2/catch.hpp>
#include <cmath>

#include "fem/beam_element.hpp"
#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

constexpr double kL = 0.37;

BeamElement element(BeamKind kind, bool rotary = false) {
  const auto p = fem_test::steel_beam(kind);
  return BeamElement(kind, kL, p.section, p.material, rotary);
}

/// The element's dof vectors of the rigid motions (translations, then rotations about x, y, z; planar: x, y,
/// z-rotation).
Eigen::MatrixXd rigid_motions(BeamKind kind) {
  if (kind == BeamKind::kPlanar) {
    Eigen::MatrixXd r = Eigen::MatrixXd::Zero(6, 3);
    r(0, 0) = r(3, 0) = 1.0;  // u
    r(1, 1) = r(4, 1) = 1.0;  // v
    r(2, 2) = r(5, 2) = 1.0;  // theta_z: v = x theta
    r(4, 2) = kL;
    return r;
  }
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(12, 6);
  for (int k = 0; k < 3; ++k) r(k, k) = r(6 + k, k) = 1.0;
  r(3, 3) = r(9, 3) = 1.0;   // theta_x
  r(4, 4) = r(10, 4) = 1.0;  // theta_y: w = -x theta
  r(8, 4) = -kL;
  r(5, 5) = r(11, 5) = 1.0;  // theta_z: v = x theta
  r(7, 5) = kL;
  return r;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("beam element: K_e is symmetric, rigid motions cost no energy, and nothing else is free",
          "[beam]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const BeamElement e = element(kind);
    const Eigen::MatrixXd k = e.stiffness();
    const Eigen::MatrixXd r = rigid_motions(kind);
    CHECK(max_abs(k - k.transpose()) == 0.0);
    CHECK(max_abs(k * r) < 1e-12 * max_abs(k));
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k).eigenvalues();
    const int rigid = static_cast<int>(r.cols());
    CHECK(std::abs(eig[rigid - 1]) < 1e-10 * eig.maxCoeff());
    CHECK(eig[rigid] > 1e-8 * eig.maxCoeff());
  }
}

TEST_CASE("beam element: bending energy of a constant curvature is E I kappa^2 L / 2", "[beam]") {
  // v = kappa x^2 / 2: v0 = 0, theta0 = 0, v1 = kappa L^2 / 2, theta1 = kappa L (exact in the cubics).
  const double kappa = 0.3;
  const auto p = fem_test::steel_beam(BeamKind::kSpatial);
  const BeamElement e = element(BeamKind::kSpatial);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(12), w = Eigen::VectorXd::Zero(12);
  v(7) = kappa * kL * kL / 2.0;
  v(11) = kappa * kL;
  w(8) = kappa * kL * kL / 2.0;
  w(10) = -kappa * kL;  // theta_y = -dw/dx
  CHECK(0.5 * v.dot(e.stiffness() * v) == Approx(0.5 * p.material.E * p.section.Iz * kappa * kappa * kL));
  CHECK(0.5 * w.dot(e.stiffness() * w) == Approx(0.5 * p.material.E * p.section.Iy * kappa * kappa * kL));
  // The wrong sign for theta_y would not be a pure curvature and cost more.
  w(10) = kappa * kL;
  CHECK(0.5 * w.dot(e.stiffness() * w) > 1.5 * 0.5 * p.material.E * p.section.Iy * kappa * kappa * kL);
}

TEST_CASE("beam element: mass from the mass points equals the closed-form consistent mass", "[beam]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial})
    for (bool rotary : {false, true}) {
      const BeamElement e = element(kind, rotary);
      const Eigen::MatrixXd closed = e.consistent_mass();
      CHECK(max_abs(e.mass() - closed) < 1e-14 * max_abs(closed));
      CHECK(max_abs(closed - closed.transpose()) == 0.0);
    }
}

TEST_CASE("beam element: rigid motions carry the mass and inertia of the bar", "[beam]") {
  const auto p = fem_test::steel_beam(BeamKind::kSpatial);
  const double rho_a = p.material.rho * p.section.A;
  const BeamElement e = element(BeamKind::kSpatial);
  const Eigen::MatrixXd m = e.mass(), r = rigid_motions(BeamKind::kSpatial);
  for (int k = 0; k < 3; ++k) CHECK(r.col(k).dot(m * r.col(k)) == Approx(rho_a * kL));
  // Turning about z (or y) at unit rate through node 0: v = x, so int rho A x^2 = rho A L^3 / 3.
  CHECK(r.col(5).dot(m * r.col(5)) == Approx(rho_a * kL * kL * kL / 3.0));
  CHECK(r.col(4).dot(m * r.col(4)) == Approx(rho_a * kL * kL * kL / 3.0));
  // Turning about x: the torsional inertia rho Ip L.
  CHECK(r.col(3).dot(m * r.col(3)) == Approx(p.material.rho * p.section.polar_moment() * kL));
}

TEST_CASE("beam element: K_G for a constant N is N / (30 L) [36 3L -36 3L; ...]", "[beam]") {
  const double n = -1234.5, L = kL;
  Eigen::Matrix4d expected;
  // clang-format off
  expected << 36, 3 * L, -36, 3 * L,
              3 * L, 4 * L * L, -3 * L, -L * L,
              -36, -3 * L, 36, -3 * L,
              3 * L, -L * L, -3 * L, 4 * L * L;
  // clang-format on
  expected *= n / (30.0 * L);
  const BeamElement e = element(BeamKind::kPlanar);
  const Eigen::MatrixXd quad = e.geometric_stiffness(Prestress{[n](double) { return n; }});
  const Eigen::MatrixXd closed = e.geometric_stiffness_linear(n, n);
  const int dofs[4] = {1, 2, 4, 5};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      CHECK(quad(dofs[i], dofs[j]) == Approx(expected(i, j)).margin(1e-12 * std::abs(n)));
      CHECK(closed(dofs[i], dofs[j]) == Approx(expected(i, j)).margin(1e-12 * std::abs(n)));
    }
  // No axial terms, and a rigid rotation costs N L theta^2 (int N v'^2 dx with v' = 1).
  CHECK(quad.row(0).norm() + quad.row(3).norm() == 0.0);
  const Eigen::MatrixXd r = rigid_motions(BeamKind::kPlanar);
  CHECK(r.col(2).dot(quad * r.col(2)) == Approx(n * L));
  CHECK((quad * r.col(1)).norm() < 1e-12 * std::abs(n));
}

TEST_CASE("beam element: K_G for a linear N, closed form against quadrature, both planes", "[beam]") {
  const double n0 = 5000.0, n1 = -800.0;
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const BeamElement e = element(kind);
    const Eigen::MatrixXd closed = e.geometric_stiffness_linear(n0, n1);
    const Eigen::MatrixXd quad =
        e.geometric_stiffness(Prestress{[=](double xi) { return n0 * (1.0 - xi) + n1 * xi; }});
    CHECK(max_abs(closed - quad) < 1e-12 * max_abs(closed));
    CHECK(max_abs(closed - closed.transpose()) == 0.0);
    // A tension that is larger at node 0 stiffens the slope there more.
    const int theta0 = kind == BeamKind::kPlanar ? 2 : 5, theta1 = kind == BeamKind::kPlanar ? 5 : 11;
    CHECK(closed(theta0, theta0) > closed(theta1, theta1));
  }
  // Spatial: the w block is the v block with theta_y = -dw/dx.
  const BeamElement e = element(BeamKind::kSpatial);
  const Eigen::MatrixXd k = e.geometric_stiffness_linear(n0, n1);
  CHECK(k(2, 2) == Approx(k(1, 1)));
  CHECK(k(2, 4) == Approx(-k(1, 5)));
  CHECK(k(4, 10) == Approx(k(5, 11)));
}

TEST_CASE("beam element: shape functions interpolate the nodal dofs and their slopes", "[beam]") {
  const BeamElement e = element(BeamKind::kSpatial);
  Eigen::VectorXd u(12);
  u << 0.1, -0.2, 0.3, 0.4, -0.5, 0.6, -0.7, 0.8, -0.9, 1.0, 1.1, -1.2;
  const ShapeSample s0 = e.shape(Eigen::Vector3d(0.0, 0.0, 0.0)),
                    s1 = e.shape(Eigen::Vector3d(1.0, 0.0, 0.0));
  CHECK((s0.N * u - u.segment(0, 3)).norm() < 1e-14);
  CHECK((s1.N * u - u.segment(6, 3)).norm() < 1e-14);
  CHECK((s0.Nrot * u - u.segment(3, 3)).norm() < 1e-14);
  CHECK((s1.Nrot * u - u.segment(9, 3)).norm() < 1e-14);
  CHECK((s1.r - Eigen::Vector3d(kL, 0.0, 0.0)).norm() < 1e-15);
  // Inside: theta_z = dv/dx and theta_y = -dw/dx, by central differences in x.
  const double xi = 0.37, h = 1e-6;
  const Eigen::Vector3d d_plus = e.shape(Eigen::Vector3d(xi + h, 0, 0)).N * u;
  const Eigen::Vector3d d_minus = e.shape(Eigen::Vector3d(xi - h, 0, 0)).N * u;
  const Eigen::Vector3d slope = (d_plus - d_minus) / (2.0 * h * kL);
  const Eigen::Vector3d theta = e.shape(Eigen::Vector3d(xi, 0, 0)).Nrot * u;
  CHECK(theta.z() == Approx(slope.y()).epsilon(1e-8));
  CHECK(theta.y() == Approx(-slope.z()).epsilon(1e-8));
  CHECK(theta.x() == Approx(u(3) * (1.0 - xi) + u(9) * xi));
}

TEST_CASE("beam element: invalid sections are rejected", "[beam]") {
  auto p = fem_test::steel_beam(BeamKind::kSpatial);
  CHECK_THROWS(BeamElement(BeamKind::kPlanar, 0.0, p.section, p.material));
  p.section.J = 0.0;
  CHECK_NOTHROW(BeamElement(BeamKind::kPlanar, 1.0, p.section, p.material));
  CHECK_THROWS(BeamElement(BeamKind::kSpatial, 1.0, p.section, p.material));
}
