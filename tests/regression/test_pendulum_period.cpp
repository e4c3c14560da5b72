// SPDX-License-Identifier: GPL-2.0-or-later
// Simple pendulum against the exact period T = 4 sqrt(l/g) K(sin(theta0/2)),
// with K the complete elliptic integral of the first kind computed by the
// arithmetic-geometric mean, K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
#include <catch2/catch.hpp>

#include <cmath>

#include "simple_pendulum.hpp"
#include "system_helpers.hpp"

namespace {

using Pendulum = kanegen_models::simple_pendulum::System;

double elliptic_k(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 60 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double next = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next;
  }
  return M_PI / (2.0 * a);
}

/// Released at rest from theta0, the pendulum is back at rest at t = T. At
/// the turning point u' = -(g/l) sin(theta0), so u(T_exact) / u' measures the
/// period's error to first order.
double period_error(const Pendulum::Params& p, double theta0) {
  const double exact = 4.0 * std::sqrt(p.l / p.g) * elliptic_k(std::sin(theta0 / 2.0));
  double x[2] = {theta0, 0.0};
  kanegen::runtime::IntegrationOptions opt;
  opt.t_end = exact;
  opt.dt = exact;
  opt.rtol = 1e-13;
  opt.atol = 1e-13;
  opt.max_steps = 1000000;
  const auto result = kanegen::runtime::integrate(kanegen::runtime::Method::kDopri5,
                                                  kanegen_test::rhs<Pendulum>(p), 0.0, x, 2, opt, nullptr);
  REQUIRE(result.ok());
  const double udot_turning = -(p.g / p.l) * std::sin(theta0);
  return std::abs(x[1] / udot_turning) / exact;
}

}  // namespace

TEST_CASE("simple pendulum period matches the elliptic-integral value", "[regression][pendulum]") {
  Pendulum::Params p;
  for (double theta0 : {0.1, 0.5, 1.5, 2.5, 3.0}) {
    INFO("theta0 = " << theta0);
    CHECK(period_error(p, theta0) < 1e-9);
  }
  // Parameters stay symbolic: a longer rod and another gravity give their own period.
  REQUIRE(Pendulum::set_parameter(p, "l", 2.5));
  REQUIRE(Pendulum::set_parameter(p, "g", 3.7));
  CHECK(period_error(p, 2.0) < 1e-9);
}

TEST_CASE("simple pendulum small-amplitude period tends to 2 pi sqrt(l/g)", "[regression][pendulum]") {
  Pendulum::Params p;
  // An independent check of the reference itself: K(0) = pi/2.
  CHECK(elliptic_k(0.0) == Approx(M_PI / 2).epsilon(1e-15));
  CHECK(4.0 * std::sqrt(p.l / p.g) * elliptic_k(std::sin(1e-4)) ==
        Approx(2 * M_PI * std::sqrt(p.l / p.g)).epsilon(1e-8));
}
