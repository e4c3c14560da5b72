// SPDX-License-Identifier: GPL-2.0-or-later
// Sparse assembly and sparse modal reduction (issue 39) against the dense
// path, which tests/fem/test_calculix_continuum.cpp holds to CalculiX: K and M
// entry by entry, frequencies to 1e-8 and mode shapes as subspaces.
#include <Eigen/Sparse>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "fem/craig_bampton.hpp"
#include "fem/mesh_body.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_modal.hpp"
#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

MeshBody data_body(const std::string& name, InpMesh& mesh) {
  mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/" + name + ".inp");
  // Steel; the plates 5 mm thick.
  return build_mesh_body(mesh, ContinuumMaterial{2.1e11, 0.3, 7850.0}, 0.005);
}

/// max |dense - sparse| over max |dense|.
double sparse_dense_difference(const Eigen::MatrixXd& dense, const Eigen::SparseMatrix<double>& sparse) {
  REQUIRE(sparse.rows() == dense.rows());
  REQUIRE(sparse.cols() == dense.cols());
  const Eigen::MatrixXd from_sparse = Eigen::MatrixXd(sparse);
  return (dense - from_sparse).cwiseAbs().maxCoeff() / dense.cwiseAbs().maxCoeff();
}

bool clustered(double a, double b) { return std::abs(b - a) <= 1e-6 * std::abs(b); }

/// The sparse path's first k modes against the dense path's (modal_analysis of the
/// dense matrices): elastic frequencies to 1e-8 relative, rigid ones (omega = 0) below
/// 1e-4 of the first elastic one, each mode of a single frequency equal to the dense
/// one (both canonically oriented), and the k modes spanning the same subspace.
void compare_paths(const MeshBody& mb, const Constraint& c, int rigid, int k) {
  const ModalBasis dense = constrained_modes(mb.body, c, -1, ModalPath::kDense);
  // Do not cut a cluster of repeated frequencies (the square bars bend alike in y and z).
  while (clustered(dense.eigenvalues[k - 1], dense.eigenvalues[k])) --k;
  const ModalBasis sparse = constrained_modes(mb.body, c, k, ModalPath::kSparse);
  REQUIRE(sparse.omega.size() == k);
  const Eigen::MatrixXd M = c.reduce(mb.body.mass());
  for (int i = 0; i < k; ++i) {
    INFO("mode " << i + 1 << ": dense " << dense.omega[i] << ", sparse " << sparse.omega[i] << " rad/s");
    if (i < rigid) {
      CHECK(sparse.omega[i] < 1e-4 * dense.omega[rigid]);
      continue;
    }
    CHECK(std::abs(sparse.omega[i] / dense.omega[i] - 1.0) < 1e-8);
    const bool single = (i == 0 || !clustered(dense.eigenvalues[i - 1], dense.eigenvalues[i])) &&
                        !clustered(dense.eigenvalues[i], dense.eigenvalues[i + 1]);
    if (single) {
      const Eigen::VectorXd d = sparse.shapes.col(i) - dense.shapes.col(i);
      CHECK(std::sqrt(d.dot(M * d)) < 1e-6);
    }
  }
  // Same subspace: the M-inner products of two M-orthonormal bases form an orthogonal matrix.
  const Eigen::MatrixXd G = dense.shapes.leftCols(k).transpose() * M * sparse.shapes;
  CHECK((G.transpose() * G - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff() < 1e-8);
  CHECK((sparse.shapes.transpose() * M * sparse.shapes - Eigen::MatrixXd::Identity(k, k))
            .cwiseAbs()
            .maxCoeff() < 1e-10);
}

}  // namespace

TEST_CASE("sparse: K and M assembled sparse equal the dense ones entrywise, every mesh family", "[sparse]") {
  for (const std::string name : {"plate_cps4", "plate_cps8", "bar_c3d8", "bar_c3d20"}) {
    INFO(name);
    InpMesh mesh;
    const MeshBody mb = data_body(name, mesh);
    const Eigen::SparseMatrix<double> Ks = sparse_stiffness(mb.body), Ms = sparse_mass(mb.body);
    CHECK(sparse_dense_difference(mb.body.stiffness(), Ks) < 1e-14);
    CHECK(sparse_dense_difference(mb.body.mass(), Ms) < 1e-14);
    // Sparse indeed: a node couples only to the nodes of its elements.
    CHECK(Ks.nonZeros() < Ks.rows() * Ks.cols() / 4);
  }
}

TEST_CASE("sparse: beams in turned frames and point masses assemble the same sparse", "[sparse]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const BeamProperties p = fem_test::steel_beam(kind);
    Body body(make_beam_chain(p, 0.9, 6).layout());
    const int first = body.add_node(Eigen::Vector3d(0.1, 0.2, 0.0));
    const Eigen::Vector3d direction = kind == BeamKind::kPlanar
                                          ? Eigen::Vector3d(std::cos(0.6), std::sin(0.6), 0.0)
                                          : Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    add_beam_run(body, first, body.node_position(first) + 0.9 * direction, 6, p,
                 kind == BeamKind::kPlanar ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(0.2, 0.9, 0.1));
    body.add_point_mass(body.num_nodes() - 1, 0.7, Eigen::Vector3d(1e-3, 2e-3, 3e-3).asDiagonal());
    body.add_point_mass(2, 0.2);
    CHECK(sparse_dense_difference(body.stiffness(), sparse_stiffness(body)) < 1e-14);
    CHECK(sparse_dense_difference(body.mass(), sparse_mass(body)) < 1e-14);
  }
}

TEST_CASE("sparse: Lanczos frequencies equal the dense path's to 1e-8, clamped and free, plate and solids",
          "[sparse]") {
  for (const std::string name : {"plate_cps8", "bar_c3d20", "bar_c3d8"}) {
    InpMesh mesh;
    const MeshBody mb = data_body(name, mesh);
    const int rigid = mb.body.dofs_per_node() == 2 ? 3 : 6;
    {
      INFO(name << " clamped at ROOT");
      compare_paths(mb, mb.clamped(mesh, "ROOT"), 0, 12);
    }
    {
      INFO(name << " free (rigid modes at 0, a negative shift)");
      compare_paths(mb, Constraint(mb.body.num_dofs(), {}), rigid, rigid + 12);
    }
  }
}

TEST_CASE("sparse: bad mode counts are refused", "[sparse]") {
  InpMesh mesh;
  const MeshBody mb = data_body("plate_cps8", mesh);
  const Constraint c = mb.clamped(mesh, "ROOT");
  CHECK_THROWS_AS(constrained_modes(mb.body, c, 0, ModalPath::kSparse), std::invalid_argument);
  CHECK_THROWS_AS(constrained_modes(mb.body, c, c.num_free(), ModalPath::kSparse), std::invalid_argument);
}

TEST_CASE("sparse: Craig-Bampton by sparse solves equals the dense basis (C3D20 bar, tip interface)",
          "[sparse]") {
  for (const std::string name : {"bar_c3d20", "plate_cps8"}) {
    INFO(name);
    InpMesh mesh;
    const MeshBody mb = data_body(name, mesh);
    std::vector<int> tip;  // the nodes of the free end's face, x = L
    double length = 0.0;
    for (int n = 0; n < mb.body.num_nodes(); ++n) length = std::max(length, mb.body.node_position(n).x());
    for (int n = 0; n < mb.body.num_nodes(); ++n)
      if (mb.body.node_position(n).x() > length * (1.0 - 1e-9)) tip.push_back(n);
    const Constraint root = mb.clamped(mesh, "ROOT");
    const int k = 6;
    const CraigBamptonBasis dense = craig_bampton(mb.body, root, {tip}, k, ModalPath::kDense);
    const CraigBamptonBasis sparse = craig_bampton(mb.body, root, {tip}, k, ModalPath::kSparse);
    REQUIRE(sparse.constraint_modes == dense.constraint_modes);
    REQUIRE(sparse.basis.cols() == dense.basis.cols());
    const Eigen::MatrixXd M = mb.body.mass();
    // The constraint modes are statics: unique, equal column by column.
    for (int j = 0; j < dense.constraint_modes; ++j) {
      const Eigen::VectorXd d = sparse.basis.col(j) - dense.basis.col(j);
      CHECK(std::sqrt(d.dot(M * d)) < 1e-8);
    }
    for (int i = 0; i < k; ++i) CHECK(std::abs(sparse.omega[i] / dense.omega[i] - 1.0) < 1e-8);
    // The fixed-interface modes: the same subspace.
    const Eigen::MatrixXd D = dense.basis.rightCols(k), S = sparse.basis.rightCols(k);
    const Eigen::MatrixXd G = D.transpose() * M * S;
    CHECK((G.transpose() * G - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff() < 1e-8);
  }
}
