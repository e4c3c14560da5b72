// SPDX-License-Identifier: GPL-2.0-or-later
// templates/solve_saddle.hpp, the saddle-point solve every generated model
// with loops contains, against Eigen's dense solve of the same system.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "solve_saddle.hpp"

namespace {

using kanegen_templates::solve_saddle;

// M (NS x NS) symmetric positive definite, C (NC x NS) of full row rank.
template <int NS, int NC>
void check_against_eigen(const Eigen::Matrix<double, NS, NS>& M, const Eigen::Matrix<double, NC, NS>& C,
                         const Eigen::Matrix<double, NS, 1>& b, const Eigen::Matrix<double, NC, 1>& g) {
  // M udot = b + C^T lambda, C udot = g.
  Eigen::Matrix<double, NS + NC, NS + NC> K = Eigen::Matrix<double, NS + NC, NS + NC>::Zero();
  K.template topLeftCorner<NS, NS>() = M;
  K.template topRightCorner<NS, NC>() = -C.transpose();
  K.template bottomLeftCorner<NC, NS>() = C;
  Eigen::Matrix<double, NS + NC, 1> rhs;
  rhs << b, g;
  const Eigen::Matrix<double, NS + NC, 1> expected = K.fullPivLu().solve(rhs);

  // Row-major copies, as the generated code passes them.
  double m[NS * NS], x[NS], c[NC * NS], gamma[NC], lambda[NC];
  for (int i = 0; i < NS; ++i) {
    x[i] = b(i);
    for (int j = 0; j < NS; ++j) m[i * NS + j] = M(i, j);
  }
  for (int r = 0; r < NC; ++r) {
    gamma[r] = g(r);
    for (int j = 0; j < NS; ++j) c[r * NS + j] = C(r, j);
  }
  REQUIRE(solve_saddle<NS, NC>(m, x, c, gamma, lambda) == 0);
  for (int i = 0; i < NS; ++i) CHECK(x[i] == Approx(expected(i)).margin(1e-12));
  for (int r = 0; r < NC; ++r) CHECK(lambda[r] == Approx(expected(NS + r)).margin(1e-12));
}

}  // namespace

TEST_CASE("the saddle-point solve agrees with a dense solve of the same system", "[saddle]") {
  Eigen::Matrix<double, 4, 4> A;
  A << 2.0, 0.3, -0.1, 0.4, 0.3, 1.5, 0.2, -0.3, -0.1, 0.2, 3.0, 0.5, 0.4, -0.3, 0.5, 1.2;
  const Eigen::Matrix<double, 4, 4> M = A * A.transpose() + Eigen::Matrix<double, 4, 4>::Identity();
  Eigen::Matrix<double, 2, 4> C;
  C << 1.0, -0.5, 0.25, 0.0, 0.0, 0.7, -1.1, 0.4;
  Eigen::Matrix<double, 4, 1> b(0.5, -1.0, 2.0, 0.3);
  Eigen::Matrix<double, 2, 1> g(0.1, -0.2);
  check_against_eigen<4, 2>(M, C, b, g);
  Eigen::Matrix<double, 1, 4> one_row = C.topRows<1>();
  check_against_eigen<4, 1>(M, one_row, b, g.head<1>());
}

TEST_CASE("the saddle-point solve reports dependent loop equations and a singular M", "[saddle]") {
  double M[4] = {2.0, 0.0, 0.0, 1.0}, b[2] = {1.0, 1.0}, lambda[2];
  const double g[2] = {0.0, 0.0};
  SECTION("a repeated loop equation: -2, the second pivot of C M^-1 C^T") {
    double C[4] = {1.0, 1.0, 1.0, 1.0};
    CHECK(solve_saddle<2, 2>(M, b, C, g, lambda) == -2);
  }
  SECTION("a loop equation whose Jacobian vanishes: -1") {
    double C[2] = {0.0, 0.0};
    CHECK(solve_saddle<2, 1>(M, b, C, g, lambda) == -1);
  }
  SECTION("M not positive definite: the pivot's index") {
    double singular[4] = {1.0, 1.0, 1.0, 1.0}, C[2] = {1.0, 0.0};
    CHECK(solve_saddle<2, 1>(singular, b, C, g, lambda) == 2);
  }
}
