// SPDX-License-Identifier: GPL-2.0-or-later
// Gauss-Legendre rules on [0, 1]: exact up to degree 2n - 1 and not beyond.
#include <catch2/catch.hpp>
#include <cmath>

#include "fem/quadrature.hpp"

using kanegen::fem::gauss_legendre;

namespace {

double integrate_power(const kanegen::fem::QuadratureRule& rule, int k) {
  double sum = 0.0;
  for (std::size_t i = 0; i < rule.points.size(); ++i) sum += rule.weights[i] * std::pow(rule.points[i], k);
  return sum;
}

}  // namespace

TEST_CASE("gauss_legendre: two points at (1 -+ 1/sqrt 3) / 2 with weights 1/2", "[quadrature]") {
  const auto rule = gauss_legendre(2);
  REQUIRE(rule.points.size() == 2);
  CHECK(rule.points[0] == Approx(0.5 - 0.5 / std::sqrt(3.0)).epsilon(1e-15));
  CHECK(rule.points[1] == Approx(0.5 + 0.5 / std::sqrt(3.0)).epsilon(1e-15));
  CHECK(rule.weights[0] == Approx(0.5).epsilon(1e-15));
  CHECK(rule.weights[1] == Approx(0.5).epsilon(1e-15));
}

TEST_CASE("gauss_legendre: n points integrate x^k exactly for k <= 2n - 1, not for k = 2n", "[quadrature]") {
  for (int n = 1; n <= 12; ++n) {
    const auto rule = gauss_legendre(n);
    INFO("n = " << n);
    for (std::size_t i = 1; i < rule.points.size(); ++i) CHECK(rule.points[i] > rule.points[i - 1]);
    for (int k = 0; k <= 2 * n - 1; ++k)
      CHECK(integrate_power(rule, k) == Approx(1.0 / (k + 1)).epsilon(1e-13));
    // The error at degree 2n, (n!)^4 / ((2n + 1) ((2n)!)^2), is still visible for n <= 6.
    if (n <= 6) CHECK(std::abs(integrate_power(rule, 2 * n) - 1.0 / (2 * n + 1)) > 1e-8);
  }
}

TEST_CASE("gauss_legendre: rejects n < 1", "[quadrature]") { CHECK_THROWS(gauss_legendre(0)); }
