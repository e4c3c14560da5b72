// SPDX-License-Identifier: GPL-2.0-or-later
// The runtime's envelope LU (runtime/src/envelope_lu.hpp), which genalpha
// uses on its iteration matrix: solutions checked by their residual A x - b
// (an independent check of any solver), on banded, dense and pivoting
// matrices; singular matrices refused with their column; the envelope
// product against the plain one.
#include "envelope_lu.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

using namespace kanegen::runtime::detail;

namespace {

using Matrix = std::vector<double>;  // n x n, row-major

/// Solves A x = b with the envelope LU and returns max |A x - b| / (|A| |x| + |b|).
double relative_residual(const Matrix& a, int n, const std::vector<double>& b) {
  Matrix lu = a, lut(n * n);
  std::vector<int> pivots(n), upper_begin(n), lower_end(n);
  int column = -1;
  REQUIRE(lu_factor(lu.data(), n, pivots.data(), &column));
  prepare_solve(lu.data(), n, lut.data(), upper_begin.data(), lower_end.data());
  std::vector<double> x = b;
  envelope_lu_solve(lut.data(), n, pivots.data(), upper_begin.data(), lower_end.data(), x.data());
  double norm_a = 0, norm_x = 0, norm_b = 0, worst = 0;
  for (int i = 0; i < n; ++i) {
    norm_x = std::max(norm_x, std::abs(x[i]));
    norm_b = std::max(norm_b, std::abs(b[i]));
    double row = 0;
    for (int j = 0; j < n; ++j) row += std::abs(a[i * n + j]);
    norm_a = std::max(norm_a, row);
  }
  for (int i = 0; i < n; ++i) {
    double r = -b[i];
    for (int j = 0; j < n; ++j) r += a[i * n + j] * x[j];
    worst = std::max(worst, std::abs(r));
  }
  return worst / (norm_a * norm_x + norm_b);
}

Matrix banded(int n, int half_band, std::mt19937_64& rng, bool dominant) {
  std::uniform_real_distribution<double> value(-1, 1);
  Matrix a(n * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - half_band); j <= std::min(n - 1, i + half_band); ++j)
      a[i * n + j] = value(rng);
  if (dominant)
    for (int i = 0; i < n; ++i) a[i * n + i] += 2 * half_band + 1;
  return a;
}

std::vector<double> random_vector(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> value(-1, 1);
  std::vector<double> v(n);
  for (double& x : v) x = value(rng);
  return v;
}

}  // namespace

TEST_CASE("envelope LU solves banded, dense and pivoting systems to round-off", "[runtime][envelope_lu]") {
  std::mt19937_64 rng(17);
  SECTION("banded and diagonally dominant, as the finite-element iteration matrices") {
    for (int n : {1, 2, 7, 31}) {
      const Matrix a = banded(n, 3, rng, true);
      CHECK(relative_residual(a, n, random_vector(n, rng)) < 1e-15);
    }
  }
  SECTION("dense and not dominant: rows are exchanged") {
    const int n = 12;
    Matrix a = banded(n, n, rng, false);
    a[0] = 0;  // the first pivot must come from another row
    Matrix lu = a;
    std::vector<int> pivots(n);
    int column = -1;
    REQUIRE(lu_factor(lu.data(), n, pivots.data(), &column));
    CHECK(pivots[0] != 0);
    CHECK(relative_residual(a, n, random_vector(n, rng)) < 1e-14);
  }
  SECTION("banded without dominance: exchanges inside the band widen the envelope") {
    const int n = 20;
    const Matrix a = banded(n, 2, rng, false);
    CHECK(relative_residual(a, n, random_vector(n, rng)) < 1e-13);
  }
  SECTION("block-diagonal: columns whose envelope is the diagonal alone") {
    const int n = 9;
    Matrix a(n * n, 0.0);
    for (int block = 0; block < 3; ++block)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[(3 * block + i) * n + 3 * block + j] = (i == j ? 4.0 : 0.5) + block;
    CHECK(relative_residual(a, n, random_vector(n, rng)) < 1e-15);
  }
}

TEST_CASE("envelope LU refuses a singular matrix and names the column", "[runtime][envelope_lu]") {
  const int n = 4;
  // Column 2 is column 0 + column 1: elimination leaves no pivot in column 2.
  Matrix a = {1, 2, 3, 0,  //
              4, 1, 5, 1,  //
              2, 2, 4, 0,  //
              0, 1, 1, 3};
  std::vector<int> pivots(n);
  int column = -1;
  CHECK_FALSE(lu_factor(a.data(), n, pivots.data(), &column));
  CHECK(column == 2);
  Matrix zero(n * n, 0.0);
  CHECK_FALSE(lu_factor(zero.data(), n, pivots.data(), &column));
  CHECK(column == 0);
}

TEST_CASE("envelope product equals the plain product", "[runtime][envelope_lu]") {
  std::mt19937_64 rng(5);
  const int n = 15;
  Matrix a = banded(n, 2, rng, false);
  for (int j = 0; j < n; ++j) a[4 * n + j] = 0;  // an empty row
  std::vector<int> begin(n), end(n);
  row_envelopes(a.data(), n, begin.data(), end.data());
  CHECK(begin[4] >= end[4]);
  CHECK(begin[0] == 0);
  CHECK(end[n - 1] == n);
  const std::vector<double> x = random_vector(n, rng);
  std::vector<double> y(n);
  envelope_multiply(a.data(), n, begin.data(), end.data(), x.data(), y.data());
  for (int i = 0; i < n; ++i) {
    double plain = 0;
    for (int j = 0; j < n; ++j) plain += a[i * n + j] * x[j];
    CHECK(y[i] == Approx(plain).margin(1e-15));
  }
}
