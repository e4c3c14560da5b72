// SPDX-License-Identifier: GPL-2.0-or-later
// Modal reduction: mass normalisation, the reduced model, and a mode
// orientation that does not depend on what the eigensolver happened to return.
#include <catch2/catch.hpp>
#include <cmath>

#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

struct Model {
  Eigen::MatrixXd M, K;
};

Model cantilever(BeamKind kind, const BeamProperties& p,
                 const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ()) {
  Body body(kind == BeamKind::kPlanar ? planar_layout() : spatial_layout());
  const int first = body.add_node(Eigen::Vector3d::Zero());
  add_beam_run(body, first, Eigen::Vector3d(1.0, 0.0, 0.0), 8, p, up);
  const Constraint c = support_constraint(body, Support::kClamped);
  return {c.reduce(body.mass()), c.reduce(body.stiffness())};
}

/// Square section: equal bending stiffness in both planes, so every bending frequency is double.
BeamProperties square_beam() {
  BeamProperties p = fem_test::steel_beam(BeamKind::kSpatial);
  const double a = 0.01;
  p.section.A = a * a;
  p.section.Iy = p.section.Iz = a * a * a * a / 12.0;
  p.section.J = 0.1406 * a * a * a * a;
  return p;
}

}  // namespace

TEST_CASE("modal: modes are mass-normalised and the reduced matrices are I and diag(omega^2)", "[modal]") {
  const Model m = cantilever(BeamKind::kSpatial, fem_test::steel_beam(BeamKind::kSpatial));
  const ModalBasis modes = modal_analysis(m.M, m.K, 10);
  REQUIRE(modes.shapes.cols() == 10);
  CHECK(max_abs(modes.reduced_mass - Eigen::MatrixXd::Identity(10, 10)) < 1e-10);
  const Eigen::MatrixXd expected_k = modes.eigenvalues.asDiagonal();
  CHECK(max_abs(modes.reduced_stiffness - expected_k) < 1e-9 * modes.eigenvalues.maxCoeff());
  for (int i = 0; i < 10; ++i) {
    CHECK(modes.omega[i] == Approx(std::sqrt(modes.eigenvalues[i])));
    if (i > 0) CHECK(modes.eigenvalues[i] >= modes.eigenvalues[i - 1]);
  }
}

TEST_CASE("modal: with all modes kept the reduced model has the full model's frequencies", "[modal]") {
  for (BeamKind kind : {BeamKind::kPlanar, BeamKind::kSpatial}) {
    const Model m = cantilever(kind, fem_test::steel_beam(kind));
    const ModalBasis full = modal_analysis(m.M, m.K);
    REQUIRE(full.shapes.cols() == m.M.rows());
    const Eigen::MatrixXd mr = full.shapes.transpose() * m.M * full.shapes;
    const Eigen::MatrixXd kr = full.shapes.transpose() * m.K * full.shapes;
    const ModalBasis reduced = modal_analysis(mr, kr);
    CHECK(max_abs(reduced.omega - full.omega) < 1e-9 * full.omega.maxCoeff());
    // Keeping k modes keeps exactly the first k frequencies.
    const ModalBasis first4 = modal_analysis(m.M, m.K, 4);
    const ModalBasis again = modal_analysis(first4.reduced_mass, first4.reduced_stiffness);
    CHECK(max_abs(again.omega - full.omega.head(4)) < 1e-9 * full.omega[3]);
  }
}

TEST_CASE("modal: each single mode has its largest-magnitude component positive", "[modal]") {
  const Model m = cantilever(BeamKind::kSpatial, fem_test::steel_beam(BeamKind::kSpatial));
  const ModalBasis modes = modal_analysis(m.M, m.K);
  for (int i = 0; i < modes.shapes.cols(); ++i) {
    Eigen::Index at;
    modes.shapes.col(i).cwiseAbs().maxCoeff(&at);
    INFO("mode " << i);
    CHECK(modes.shapes(at, i) > 0.0);
  }
}

TEST_CASE("modal: the orientation survives sign flips, rotations of degenerate pairs and rescaling",
          "[modal]") {
  const Model m = cantilever(BeamKind::kSpatial, square_beam());
  const ModalBasis modes = modal_analysis(m.M, m.K);
  // The square section makes the bending modes come in pairs.
  REQUIRE(modes.eigenvalues[1] == Approx(modes.eigenvalues[0]).epsilon(1e-10));
  // Scramble: flip every other mode, rotate the first two pairs by arbitrary angles.
  Eigen::MatrixXd scrambled = modes.shapes;
  for (int i = 0; i < scrambled.cols(); i += 2) scrambled.col(i) *= -1.0;
  for (int pair : {0, 2}) {
    const double a = 0.4 + pair;
    const Eigen::VectorXd c0 = scrambled.col(pair), c1 = scrambled.col(pair + 1);
    scrambled.col(pair) = std::cos(a) * c0 + std::sin(a) * c1;
    scrambled.col(pair + 1) = -std::sin(a) * c0 + std::cos(a) * c1;
  }
  REQUIRE(max_abs(scrambled - modes.shapes) > 0.1);
  canonicalize_modes(m.M, modes.eigenvalues, scrambled);
  CHECK(max_abs(scrambled - modes.shapes) < 1e-9 * max_abs(modes.shapes));
  // A stiffer copy has the same shapes and frequencies twice as high.
  const ModalBasis stiffer = modal_analysis(m.M, 4.0 * m.K);
  CHECK(max_abs(stiffer.shapes - modes.shapes) < 1e-8 * max_abs(modes.shapes));
  CHECK(max_abs(stiffer.omega - 2.0 * modes.omega) < 1e-9 * stiffer.omega.maxCoeff());
}

TEST_CASE("modal: the same beam built with a rolled section frame gives the same modes", "[modal]") {
  // Rolling a square section about its axis changes the rounding of M and K, not the physics.
  const Model a = cantilever(BeamKind::kSpatial, square_beam());
  const Model b = cantilever(BeamKind::kSpatial, square_beam(), Eigen::Vector3d(0.0, -0.5, std::sqrt(0.75)));
  REQUIRE(max_abs(a.K - b.K) > 0.0);
  REQUIRE(max_abs(a.K - b.K) < 1e-9 * max_abs(a.K));
  const ModalBasis ma = modal_analysis(a.M, a.K), mb = modal_analysis(b.M, b.K);
  CHECK(max_abs(ma.shapes - mb.shapes) < 1e-6 * max_abs(ma.shapes));
}

TEST_CASE("modal: a massless dof (a singular M, as a reduced mass quadrature gives) is condensed, not a mode",
          "[modal]") {
  // With M = diag(I, 0) the massless dof follows the others statically, so the modes are those of Guyan's
  // exact condensation K_aa - K_ab K_bb^-1 K_ba with M_aa = I: 2 modes of 3, whose values are computed here
  // from the 2 x 2 condensed matrix by its closed form.
  Eigen::MatrixXd K(3, 3);
  K << 4.0, 1.0, 1.0, 1.0, 3.0, 1.0, 1.0, 1.0, 2.0;
  const Eigen::MatrixXd M = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  const double a = 4.0 - 0.5, b = 1.0 - 0.5, d = 3.0 - 0.5;  // K_aa - K_ab K_ba / K_bb
  const double mean = (a + d) / 2.0, radius = std::sqrt((a - d) * (a - d) / 4.0 + b * b);
  const ModalBasis all = modal_analysis(M, K);
  REQUIRE(all.eigenvalues.size() == 2);
  CHECK(all.eigenvalues[0] == Approx(mean - radius).epsilon(1e-10));
  CHECK(all.eigenvalues[1] == Approx(mean + radius).epsilon(1e-10));
  CHECK(max_abs(all.reduced_mass - Eigen::MatrixXd::Identity(2, 2)) < 1e-10);
  for (int j = 0; j < 2; ++j)  // K phi = lambda M phi also in the massless row
    CHECK((K * all.shapes.col(j) - all.eigenvalues[j] * M * all.shapes.col(j)).norm() < 1e-9);
  CHECK_THROWS_WITH(modal_analysis(M, K, 3), Catch::Contains("only 2 of the 3 have mass"));
}
