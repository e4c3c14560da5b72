// SPDX-License-Identifier: GPL-2.0-or-later
// The generator's view of a body: nodal or modal coordinates with names,
// reduced matrices, invariants and geometric stiffness; section resultants.
#include <catch2/catch.hpp>
#include <cmath>

#include "fem/beam_element.hpp"
#include "fem/reduction.hpp"
#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("reduction: nodal coordinates are the free dofs, named by node and component", "[reduction]") {
  const Body body = make_beam_chain(fem_test::steel_beam(BeamKind::kPlanar), 1.0, 3);
  const Constraint c = support_constraint(body, Support::kClamped);
  const ReducedBody r = reduce_nodal(body, c);
  REQUIRE(r.names.size() == 9);
  CHECK(r.names.front() == "n1.u");
  CHECK(r.names[1] == "n1.v");
  CHECK(r.names.back() == "n3.theta_z");
  CHECK(max_abs(r.mass - c.reduce(body.mass())) == 0.0);
  CHECK(max_abs(r.stiffness - c.reduce(body.stiffness())) == 0.0);
  REQUIRE(r.geometric.has_value());
  CHECK(max_abs(r.geometric->linear - c.reduce(geometric_stiffness_basis(body).linear)) == 0.0);
  CHECK(max_abs(r.node_translation(body, 3) - body.node_translation(3)(Eigen::all, c.free())) == 0.0);
  CHECK(r.omega.size() == 0);
}

TEST_CASE("reduction: modal coordinates are mass-normalised and keep the first frequencies", "[reduction]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  const Body body = make_beam_chain(p, 1.0, 10);
  const Constraint c = support_constraint(body, Support::kClamped);
  const ReducedBody r = reduce_modal(body, c, 5);
  REQUIRE(r.names == std::vector<std::string>{"mode1", "mode2", "mode3", "mode4", "mode5"});
  CHECK(max_abs(r.mass - Eigen::MatrixXd::Identity(5, 5)) < 1e-10);
  CHECK(max_abs(r.invariants.elastic_mass() - Eigen::MatrixXd::Identity(5, 5)) < 1e-10);
  const Eigen::VectorXd full = fem_test::frequencies(c, body.mass(), body.stiffness());
  CHECK(max_abs(r.omega - full.head(5)) < 1e-9 * full[4]);
  CHECK(max_abs(Eigen::MatrixXd(r.stiffness.diagonal()) - Eigen::MatrixXd(r.omega.cwiseAbs2())) <
        1e-8 * r.omega[4] * r.omega[4]);
  // The clamp holds in every mode.
  CHECK(max_abs(r.node_translation(body, 0)) == 0.0);
  // An L-frame is no chain on x: no chain geometric stiffness, but everything else.
  Body frame(spatial_layout());
  const int corner =
      add_beam_run(frame, frame.add_node(Eigen::Vector3d::Zero()), Eigen::Vector3d(1, 0, 0), 3, p);
  add_beam_run(frame, corner, Eigen::Vector3d(1, 1, 0), 3, p);
  const ReducedBody rf = reduce_modal(frame, support_constraint(frame, Support::kClamped), 3);
  CHECK(!rf.geometric.has_value());
  CHECK(rf.invariants.n == 3);
}

TEST_CASE("reduction: four modes carry the rotating beam's stiffening", "[reduction]") {
  // Flapwise lambda = 10 with the K_G basis in modal coordinates: first two within 0.5 % of the table.
  const BeamProperties p = fem_test::steel_beam(BeamKind::kPlanar);
  const double L = 1.0, rho_a = p.material.rho * p.section.A, EI = p.material.E * p.section.Iz;
  const Body body = make_beam_chain(p, L, 10);
  const ReducedBody r = reduce_modal(body, support_constraint(body, Support::kClamped), 4);
  const double scale = std::sqrt(EI / (rho_a * std::pow(L, 4))), omega = 10.0 * scale;
  const Eigen::MatrixXd k = r.stiffness + omega * omega * r.geometric->linear;
  const Eigen::VectorXd w = modal_analysis(r.mass, k).omega / scale;
  CHECK(std::abs(w[0] / 11.2023 - 1.0) < 5e-3);
  CHECK(std::abs(w[1] / 33.6404 - 1.0) < 5e-3);
  // Without the stiffening they stay at the non-rotating values.
  CHECK(std::abs(r.omega[0] / scale / 3.5160 - 1.0) < 1e-3);
}

TEST_CASE("beam element: section resultants of a cantilever under tip loads", "[beam]") {
  const BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  const double L = 0.8, P = 25.0;
  const Body body = make_beam_chain(p, L, 4);
  const Constraint c = support_constraint(body, Support::kClamped);
  const int tip = body.num_nodes() - 1;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(body.num_dofs());
  f[body.dof(tip, DofKind::kUx)] = 3.0 * P;  // tension
  f[body.dof(tip, DofKind::kRx)] = 0.5 * P;  // torque
  f[body.dof(tip, DofKind::kUy)] = P;        // M_z(x) = P (L - x)
  f[body.dof(tip, DofKind::kUz)] = 2.0 * P;  // M_y(x) = -2 P (L - x)
  const Eigen::VectorXd u = c.expand(c.reduce(body.stiffness()).ldlt().solve(Eigen::VectorXd(f(c.free()))));
  for (int e = 0; e < body.num_elements(); ++e) {
    const ElementPlacement& placed = body.element(e);
    const auto& beam = static_cast<const BeamElement&>(*placed.element);
    const Eigen::VectorXd ue = placed.T * u(placed.dofs);
    for (double xi : {0.0, 0.5, 1.0}) {
      const double x = placed.origin.x() + xi * beam.length();
      const Eigen::VectorXd s = beam.resultant_matrix(xi) * ue;
      INFO("element " << e << " xi " << xi);
      CHECK(s[0] == Approx(3.0 * P));
      CHECK(s[1] == Approx(0.5 * P));
      CHECK(s[2] == Approx(-2.0 * P * (L - x)).margin(1e-9 * P * L));
      CHECK(s[3] == Approx(P * (L - x)).margin(1e-9 * P * L));
    }
  }
}
