// SPDX-License-Identifier: GPL-2.0-or-later
// Assembly into a body: element frames, boundary conditions, point masses.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "fem_test_support.hpp"

using namespace kanegen::fem;
using fem_test::rel_error;

namespace {

constexpr double kLength = 0.9;

/// Cantilever with a tip mass m_t (no tip inertia): roots of
/// 1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0, mu = m_t / (rho A L), b = beta L.
double tip_mass_beta_l(double mu, double lo, double hi) {
  auto f = [mu](double b) {
    return 1.0 + std::cos(b) * std::cosh(b) +
           mu * b * (std::cos(b) * std::sinh(b) - std::sin(b) * std::cosh(b));
  };
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(lo) * f(mid) <= 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("assembly: pinned-pinned beams give (n pi)^2 sqrt(E I / (rho A L^4)) within 0.1 %", "[assembly]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const BeamProperties p = fem_test::steel_beam(kind);
    const Body body = make_beam_chain(p, kLength, 10);
    const Constraint c = support_constraint(body, Support::kPinnedPinned);
    const int last = body.num_nodes() - 1;
    if (kind == BeamKind::kPlanar) {
      CHECK(c.fixed() == std::vector<int>{0, 1, body.dof(last, DofKind::kUy)});
    } else {
      CHECK(c.fixed() ==
            std::vector<int>{0, 1, 2, 3, body.dof(last, DofKind::kUy), body.dof(last, DofKind::kUz)});
    }
    const Eigen::MatrixXd M = body.mass(), K = body.stiffness();
    const double rho_a = p.material.rho * p.section.A;
    struct {
      std::vector<DofKind> kinds;
      double EI;
    } planes[] = {{{DofKind::kUy, DofKind::kRz}, p.material.E * p.section.Iz},
                  {{DofKind::kUz, DofKind::kRy}, p.material.E * p.section.Iy}};
    for (int plane = 0; plane < (kind == BeamKind::kPlanar ? 1 : 2); ++plane) {
      const auto omega = fem_test::frequencies_of(body, c, M, K, planes[plane].kinds);
      for (int n = 1; n <= 3; ++n) {
        const double exact = fem_test::bending_omega(n * M_PI, planes[plane].EI, rho_a, kLength);
        INFO("plane " << plane << " mode " << n);
        CHECK(std::abs(rel_error(omega[n - 1], exact)) < 1e-3);
      }
    }
    // The supports leave no rigid motion: the lowest frequency is the first bending one (or torsion).
    CHECK(fem_test::frequencies(c, M, K)[0] > 1.0);
  }
}

TEST_CASE("assembly: a chain turned in the link frame has the same frequencies", "[assembly]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const BeamProperties p = fem_test::steel_beam(kind);
    const Body straight = make_beam_chain(p, kLength, 6);
    const Eigen::VectorXd reference = fem_test::frequencies(support_constraint(straight, Support::kClamped),
                                                            straight.mass(), straight.stiffness());
    Body turned(straight.layout());
    const Eigen::Vector3d direction = kind == BeamKind::kPlanar
                                          ? Eigen::Vector3d(std::cos(0.6), std::sin(0.6), 0.0)
                                          : Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    // Spatial: `up` fixes the section's roll, so pick it as the turned image of z.
    const Eigen::Matrix3d R = beam_frame(
        direction, kind == BeamKind::kPlanar ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(0.2, 0.9, 0.1));
    const int first = turned.add_node(Eigen::Vector3d(0.1, 0.2, 0.0));
    add_beam_run(turned, first, turned.node_position(first) + kLength * direction, 6, p,
                 kind == BeamKind::kPlanar ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(0.2, 0.9, 0.1));
    REQUIRE((turned.element(0).R - R).norm() < 1e-14);
    const Eigen::VectorXd omega = fem_test::frequencies(support_constraint(turned, Support::kClamped),
                                                        turned.mass(), turned.stiffness());
    CHECK((omega - reference).cwiseAbs().maxCoeff() < 1e-9 * reference.maxCoeff());
    // The rigid translation along the beam stretches nothing and carries the whole mass.
    Eigen::VectorXd along = Eigen::VectorXd::Zero(turned.num_dofs());
    for (int node = 0; node < turned.num_nodes(); ++node)
      along += turned.node_translation(node).transpose() * direction;
    CHECK((turned.stiffness() * along).norm() < 1e-9 * turned.stiffness().norm());
    CHECK(along.dot(turned.mass() * along) == Approx(p.material.rho * p.section.A * kLength));
  }
}

TEST_CASE("assembly: elements that do not fit the body are rejected", "[assembly]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  Body body(planar_layout());
  const int a = body.add_node(Eigen::Vector3d::Zero());
  const int b = body.add_node(Eigen::Vector3d(1.0, 0.0, 0.0));
  const auto beam = std::make_shared<const BeamElement>(BeamKind::kPlanar, 1.0, p.section, p.material);
  CHECK_NOTHROW(body.add_element(beam, {a, b}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()));
  // Wrong length for the nodes.
  const auto short_beam = std::make_shared<const BeamElement>(BeamKind::kPlanar, 0.5, p.section, p.material);
  CHECK_THROWS(body.add_element(short_beam, {a, b}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()));
  // A planar body cannot take an element tilted out of its plane.
  const int c = body.add_node(Eigen::Vector3d(1.0, 0.0, 1.0));
  CHECK_THROWS(add_beam_run(body, b, body.node_position(c), 1, p, Eigen::Vector3d::UnitY()));
  // Nor a spatial element.
  const auto spatial = std::make_shared<const BeamElement>(
      BeamKind::kSpatial, 1.0, fem_test::steel_beam(BeamKind::kSpatial).section, p.material);
  CHECK_THROWS(body.add_element(spatial, {a, b}, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()));
}

TEST_CASE("assembly: a tip mass lowers the first frequency as the exact solution says", "[assembly]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const double rho_a = p.material.rho * p.section.A, EI = p.material.E * p.section.Iz;
  for (double mu : {0.2, 1.0}) {
    Body body = make_beam_chain(p, kLength, 10);
    body.add_point_mass(body.num_nodes() - 1, mu * rho_a * kLength);
    const auto omega = fem_test::frequencies_of(body, support_constraint(body, Support::kClamped),
                                                body.mass(), body.stiffness(), {DofKind::kUy, DofKind::kRz});
    const double b1 = tip_mass_beta_l(mu, 0.5, 1.875104);
    const double b2 = tip_mass_beta_l(mu, 2.0, 4.694091);
    INFO("mu = " << mu << ", beta1 L = " << b1 << ", beta2 L = " << b2);
    CHECK(std::abs(rel_error(omega[0], fem_test::bending_omega(b1, EI, rho_a, kLength))) < 1e-4);
    CHECK(std::abs(rel_error(omega[1], fem_test::bending_omega(b2, EI, rho_a, kLength))) < 1e-3);
  }
}

TEST_CASE("assembly: constraint maps between full and reduced dofs", "[assembly]") {
  const Constraint c(6, {4, 1, 4});
  CHECK(c.fixed() == std::vector<int>{1, 4});
  CHECK(c.free() == std::vector<int>{0, 2, 3, 5});
  CHECK(c.reduced_index(3) == 2);
  CHECK(c.reduced_index(4) == -1);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(6, 6);
  const Eigen::MatrixXd p = c.selection();
  CHECK((c.reduce(a) - p.transpose() * a * p).norm() == 0.0);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(4);
  CHECK((c.expand(x) - p * x).norm() == 0.0);
  CHECK_THROWS(Constraint(3, {3}));
}

TEST_CASE("assembly: node selectors agree with the element shape functions at the nodes", "[assembly]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  Body body(spatial_layout());
  const int first = body.add_node(Eigen::Vector3d::Zero());
  const Eigen::Vector3d end(0.2, 0.7, -0.3);
  add_beam_run(body, first, end, 2, p);
  const Eigen::VectorXd u = Eigen::VectorXd::Random(body.num_dofs());
  const MassPointGroup g = body.element_mass_points(1);
  REQUIRE(!g.points.empty());
  // Element 1 runs from node 1 to node 2; its shape at xi = 1 (link frame) is node 2's motion.
  const ElementPlacement& placed = body.element(1);
  const ShapeSample s = placed.element->shape(Eigen::Vector3d(1.0, 0.0, 0.0));
  const Eigen::VectorXd ue = u(placed.dofs);
  CHECK((placed.R * s.N * placed.T * ue - body.node_translation(2) * u).norm() < 1e-12);
  CHECK((placed.R * s.Nrot * placed.T * ue - body.node_rotation(2) * u).norm() < 1e-12);
  CHECK((placed.origin + placed.R * s.r - end).norm() < 1e-12);
}
