// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/quadrature.hpp"

#include <cmath>
#include <stdexcept>

namespace kanegen::fem {

QuadratureRule gauss_legendre(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: need at least one point");
  QuadratureRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  // Roots of P_n on [-1, 1] are symmetric; find the upper half by Newton from
  // the Tricomi estimate, then map t -> (1 + t) / 2 (weights halve).
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double t = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = t;  // P_0, P_1; the recurrence gives P_n in p1
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - t * t) * dp * dp);
    rule.points[i] = 0.5 * (1.0 - t);
    rule.points[n - 1 - i] = 0.5 * (1.0 + t);
    rule.weights[i] = rule.weights[n - 1 - i] = 0.5 * w;
  }
  return rule;
}

}  // namespace kanegen::fem
