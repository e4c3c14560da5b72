// SPDX-License-Identifier: GPL-2.0-or-later
// The foreshortening of beam bodies (fem/foreshortening.hpp) against two
// independent statements of the same second-order geometry: a small rigid
// rotation by theta moves every point by theta x r + 1/2 theta x (theta x r)
// to second order, and the work of an axial load field through the
// foreshortening is the geometric stiffness of the load's axial force
// (fem/rotating.hpp, K_G = int N(x) G^T G dx by its own quadrature).
#include <catch2/catch.hpp>
#include <cmath>

#include "fem/beam_body.hpp"
#include "fem/foreshortening.hpp"
#include "fem/invariants.hpp"
#include "fem/rotating.hpp"
#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

/// Body dofs of a small rigid rotation theta about node 0 (the root, where
/// the body is held): node translations theta x (r - r_0) and rotations theta.
Eigen::VectorXd rigid_rotation(const Body& body, const Eigen::Vector3d& theta) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(body.num_dofs());
  for (int node = 0; node < body.num_nodes(); ++node) {
    const Eigen::Vector3d t = theta.cross(body.node_position(node) - body.node_position(0));
    for (int k = 0; k < body.dofs_per_node(); ++k) {
      const DofKind kind = body.layout()[k];
      const int axis = static_cast<int>(kind) % 3;
      u[body.dof(node, k)] = static_cast<int>(kind) < 3 ? t[axis] : theta[axis];
    }
  }
  return u;
}

double largest(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

/// The foreshortening of the rotation equals the rotation's second-order
/// term 1/2 theta x (theta x (r - r_0)), at every node and in the mass integrals.
void check_rigid_rotation(const Body& body, const Eigen::Vector3d& theta) {
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(body.num_dofs(), body.num_dofs());
  const Foreshortening f = foreshortening(body, identity);
  const Eigen::VectorXd u = rigid_rotation(body, theta);
  const Eigen::Vector3d root = body.node_position(0);
  const auto second_order = [&](const Eigen::Vector3d& r) -> Eigen::Vector3d {
    return 0.5 * theta.cross(theta.cross(r - root));
  };
  const double scale = theta.squaredNorm();
  for (int node = 0; node < body.num_nodes(); ++node) {
    const Eigen::Vector3d expected = second_order(body.node_position(node));
    INFO("node " << node << " at " << body.node_position(node).transpose());
    for (int a = 0; a < 3; ++a)
      CHECK(-0.5 * u.dot(f.node[node][a] * u) == Approx(expected[a]).margin(1e-12 * scale));
  }
  // f = W (r - r_0) with W = 1/2 skew(theta)^2: sum m f = W (s - m r_0),
  // sum m f_a r_b = (W (sum m r r^T - r_0 s^T))_ab.
  const Eigen::Matrix3d w = 0.5 * skew(theta) * skew(theta);
  const InertiaInvariants inv = body_invariants(body);
  const Eigen::Vector3d first = w * (inv.first_moment - inv.mass * root);
  const Eigen::Matrix3d moments = w * (inv.second_moment - root * inv.first_moment.transpose());
  for (int a = 0; a < 3; ++a) {
    CHECK(-0.5 * u.dot(f.mass[a] * u) == Approx(first[a]).margin(1e-12 * scale * inv.mass));
    for (int b = 0; b < 3; ++b) {
      const double expected = moments(a, b);
      CHECK(-0.5 * u.dot(f.moment[3 * a + b] * u) == Approx(expected).margin(1e-12 * scale * inv.mass));
    }
  }
}

}  // namespace

TEST_CASE("foreshortening: a small rigid rotation's second-order term, on chains and an L-frame",
          "[foreshortening]") {
  const BeamProperties planar = fem_test::steel_beam(BeamKind::kPlanar);
  const BeamProperties spatial = fem_test::steel_beam(BeamKind::kSpatial);
  SECTION("a planar chain turned about z, starting off the origin") {
    Body body = make_beam_chain(planar, 1.2, 6, 0.3);
    body.add_point_mass(body.num_nodes() - 1, 0.4);
    check_rigid_rotation(body, {0.0, 0.0, 0.01});
  }
  SECTION("a spatial chain turned about y and z (no twist, whose second order the beam leaves out)") {
    const Body body = make_beam_chain(spatial, 0.8, 5);
    check_rigid_rotation(body, {0.0, 0.02, -0.01});
  }
  SECTION("a planar L-frame: the first leg's shortening carries the second leg") {
    Body body(planar_layout());
    const int corner = add_beam_run(body, body.add_node(Eigen::Vector3d::Zero()), {1.0, 0.0, 0.0}, 4, planar);
    add_beam_run(body, corner, {1.0, 0.7, 0.0}, 3, planar);
    check_rigid_rotation(body, {0.0, 0.0, 0.015});
  }
  SECTION("a spatial L-frame turned about z") {
    Body body(spatial_layout());
    const int corner =
        add_beam_run(body, body.add_node(Eigen::Vector3d::Zero()), {0.9, 0.0, 0.0}, 3, spatial);
    add_beam_run(body, corner, {0.9, 0.6, 0.0}, 3, spatial);
    check_rigid_rotation(body, {0.0, 0.0, -0.02});
  }
}

TEST_CASE("foreshortening: the work of axial loads through it is their geometric stiffness",
          "[foreshortening]") {
  for (const BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const BeamProperties p = fem_test::steel_beam(kind);
    Body body = make_beam_chain(p, 1.5, 7, 0.25);
    const int tip = body.num_nodes() - 1;
    body.add_point_mass(tip, 0.3);
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(body.num_dofs(), body.num_dofs());
    const Foreshortening f = foreshortening(body, identity);
    // A load a(x) = a_const + a_lin x per unit mass along +x: its work through
    // f_x = -1/2 u^T H_x u is -1/2 u^T (sum m a H_x) u, so K_G = a_const Fm_x + a_lin Fr_xx.
    const double a_const = -3.0, a_lin = 11.0;
    const Eigen::MatrixXd kg = body.geometric_stiffness(chain_axial_force(body, a_const, a_lin));
    const Eigen::MatrixXd from_shortening = a_const * f.mass[0] + a_lin * f.moment[0];
    CHECK(largest(from_shortening - kg) <= 1e-10 * largest(kg));
    // A unit axial force on a node does the work of node_force_geometric_stiffness.
    for (int node : {3, tip}) {
      const Eigen::MatrixXd unit = node_force_geometric_stiffness(body, node);
      CHECK(largest(f.node[node][0] - unit) <= 1e-12 * largest(unit));
      CHECK(largest(f.node[node][1]) == 0.0);
      CHECK(largest(f.node[node][2]) == 0.0);
    }
  }
}

TEST_CASE("foreshortening: in reduced coordinates it is B^T H B", "[foreshortening]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const Body body = make_beam_chain(p, 1.0, 4);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(body.num_dofs(), body.num_dofs());
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(body.num_dofs(), 3);
  const Foreshortening full = foreshortening(body, identity), reduced = foreshortening(body, B);
  CHECK(largest(reduced.mass[0] - B.transpose() * full.mass[0] * B) <= 1e-12 * largest(reduced.mass[0]));
  CHECK(largest(reduced.node[4][0] - B.transpose() * full.node[4][0] * B) <=
        1e-12 * largest(reduced.node[4][0]));
}
