// SPDX-License-Identifier: GPL-2.0-or-later
// The second-order displacement field of mesh bodies
// (fem/continuum_foreshortening.hpp) against an independent statement of the
// same physics: by reciprocity, any load f works through u2 as
// f . u2 = -1/2 eta^T Phi^T K_sigma(f) Phi eta, K_sigma(f) the geometric
// stiffness of the static stress of f, which fem/continuum_prestress.hpp
// forms by its own route (stress recovery, then int G^T S G dV). Checked
// pair by pair (f . d_ij against -(Phi^T K_sigma Phi)_ij), and through the
// Foreshortening's mass and moment integrals, for a centrifugal and a uniform
// acceleration load on clamped CPS4 and CPS8 plates and a C3D8 bar.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "fem/continuum_foreshortening.hpp"
#include "fem/continuum_prestress.hpp"
#include "fem/invariants.hpp"
#include "fem/mesh_body.hpp"
#include "fem/reduction.hpp"

using namespace kanegen::fem;

namespace {

const ContinuumMaterial kSteel{2.1e11, 0.3, 7850.0};

/// int rho N^T a dV: the consistent mass times the rigid translation a.
Eigen::VectorXd acceleration_load(const Body& body, const Eigen::Vector3d& a) {
  Eigen::VectorXd rigid = Eigen::VectorXd::Zero(body.num_dofs());
  for (int node = 0; node < body.num_nodes(); ++node)
    for (int k = 0; k < body.dofs_per_node(); ++k) rigid[body.dof(node, k)] = a[k];
  return body.mass() * rigid;
}

/// A_ij = f . d_ij.
Eigen::MatrixXd work_through_fields(const Eigen::VectorXd& f, const Eigen::MatrixXd& d, int n) {
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = f.dot(d.col(pair_index(i, j, n)));
  return a;
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

void check_reciprocity(const std::string& file, double thickness, const Eigen::Vector3d& omega,
                       const Eigen::Vector3d& acceleration) {
  INFO(file);
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/" + file);
  const MeshBody mb = build_mesh_body(mesh, kSteel, thickness);
  const Constraint root = mb.clamped(mesh, "ROOT");
  const int n = 4;
  const Eigen::MatrixXd phi = reduce_modal(mb.body, root, n).basis;
  const Eigen::MatrixXd d = second_order_fields(mb.body, root, phi);
  REQUIRE(d.cols() == 10);
  for (int dof : root.fixed()) CHECK(d.row(dof).isZero(0.0));
  const Foreshortening fs = continuum_foreshortening(mb.body, d, n, {});

  // Centrifugal: f . d_ij = -(Phi^T K_sigma Phi)_ij = sum_ab (W^2)_ab moment_ab.
  const Eigen::VectorXd fc = centrifugal_load(mb.body, omega);
  const Eigen::MatrixXd kc = phi.transpose() * load_geometric_stiffness(mb.body, root, fc) * phi;
  CHECK(relative(work_through_fields(fc, d, n), -kc) < 1e-10);
  const Eigen::Matrix3d w2 = skew(omega) * skew(omega);
  Eigen::MatrixXd from_moment = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) from_moment += w2(a, b) * fs.moment[3 * a + b];
  CHECK(relative(from_moment, -kc) < 1e-10);

  // Uniform acceleration: f . d_ij = -(Phi^T K_sigma Phi)_ij = -sum_a acc_a mass_a.
  const Eigen::VectorXd fa = acceleration_load(mb.body, acceleration);
  const Eigen::MatrixXd ka = phi.transpose() * load_geometric_stiffness(mb.body, root, fa) * phi;
  CHECK(relative(work_through_fields(fa, d, n), -ka) < 1e-10);
  Eigen::MatrixXd from_mass = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < 3; ++a) from_mass += acceleration[a] * fs.mass[a];
  CHECK(relative(from_mass, ka) < 1e-10);
}

}  // namespace

TEST_CASE("mesh foreshortening: a load works through u2 as -1/2 eta^T Phi^T K_sigma Phi eta",
          "[mesh_foreshortening]") {
  check_reciprocity("plate_cps4.inp", 0.002, {0.0, 0.0, 40.0}, {3.0, -9.81, 0.0});
  check_reciprocity("plate_cps8.inp", 0.002, {0.0, 0.0, 40.0}, {-2.0, 9.81, 0.0});
  check_reciprocity("bar_c3d8.inp", 1.0, {12.0, -20.0, 35.0}, {4.0, 1.0, -9.81});
}

TEST_CASE("mesh foreshortening: H at a point is -(its displacement operator) times d_ij",
          "[mesh_foreshortening]") {
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/plate_cps8.inp");
  const MeshBody mb = build_mesh_body(mesh, kSteel, 0.002);
  const Constraint root = mb.clamped(mesh, "ROOT");
  const int n = 3;
  const Eigen::MatrixXd phi = reduce_modal(mb.body, root, n).basis;
  const Eigen::MatrixXd d = second_order_fields(mb.body, root, phi);
  const int last = mb.body.num_nodes() - 1;
  const Foreshortening fs = continuum_foreshortening(mb.body, d, n, {mb.body.node_translation(last)});
  const Eigen::VectorXd eta = Eigen::Vector3d(0.3, -0.2, 0.1);
  Eigen::VectorXd u2 = Eigen::VectorXd::Zero(mb.body.num_dofs());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) u2 += 0.5 * eta[i] * eta[j] * d.col(pair_index(i, j, n));
  for (int a = 0; a < 2; ++a)
    CHECK(-0.5 * eta.dot(fs.node[0][a] * eta) == Approx(u2[mb.body.dof(last, a)]).epsilon(1e-12));
  CHECK(fs.node[0][2].isZero(0.0));  // a plane body stays in its plane
}

TEST_CASE("mesh foreshortening: a body free to move rigidly has no held reference", "[mesh_foreshortening]") {
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/plate_cps4.inp");
  const MeshBody mb = build_mesh_body(mesh, kSteel, 0.002);
  const Constraint free(mb.body.num_dofs(), {});
  const Eigen::MatrixXd phi = Eigen::MatrixXd::Random(mb.body.num_dofs(), 2);
  CHECK_THROWS_WITH(second_order_fields(mb.body, free, phi), Catch::Contains("free to move rigidly"));
}

TEST_CASE("mesh foreshortening: the elastic mass's second-order integrals are Phi^T M d and d^T M d",
          "[mesh_foreshortening]") {
  // add_second_order_mass sums over the mass points; the body's consistent
  // mass matrix (element by element, with its own scatter) gives the same
  // integrals as matrix products, and d^T M d is positive semidefinite.
  for (const char* file : {"plate_cps8.inp", "bar_c3d8.inp"}) {
    INFO(file);
    const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/" + file);
    const MeshBody mb = build_mesh_body(mesh, kSteel, 0.002);
    const Constraint root = mb.clamped(mesh, "ROOT");
    const int n = 3;
    const Eigen::MatrixXd phi = reduce_modal(mb.body, root, n).basis;
    const Eigen::MatrixXd d = second_order_fields(mb.body, root, phi);
    Foreshortening fs = continuum_foreshortening(mb.body, d, n, {});
    add_second_order_mass(mb.body, phi, d, fs);
    const Eigen::MatrixXd m = mb.body.mass();
    // Entry by entry against the Cauchy-Schwarz bound sqrt(phi_k^T M phi_k d_p^T M d_p): the modes
    // and the fields are nearly M-orthogonal, so the largest entry is no scale for the round-off.
    const Eigen::MatrixXd cross = phi.transpose() * m * d, squares = d.transpose() * m * d;
    const Eigen::VectorXd mode_norm = (phi.transpose() * m * phi).diagonal().cwiseSqrt(),
                          field_norm = squares.diagonal().cwiseSqrt();
    CHECK(((fs.mode_pair - cross).array() / (mode_norm * field_norm.transpose()).array()).abs().maxCoeff() <
          1e-12);
    CHECK(
        ((fs.pair_pair - squares).array() / (field_norm * field_norm.transpose()).array()).abs().maxCoeff() <
        1e-12);
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(fs.pair_pair).eigenvalues();
    CHECK(lambda.minCoeff() > -1e-12 * lambda.maxCoeff());
    CHECK_THROWS_AS(add_second_order_mass(mb.body, phi, d.leftCols(2), fs), std::invalid_argument);
  }
}
