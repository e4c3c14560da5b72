// SPDX-License-Identifier: GPL-2.0-or-later
// Central differences with one Richardson step, for checking emitted
// Jacobians (constraint Jacobians of closed loops, when the kernels have
// them) against the function they differentiate. Error O(h^4) plus
// round-off of order eps |g| / h.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace kanegen::numeric {

/// g: R^n -> R^m. Returns the m x n Jacobian at x, row-major.
inline std::vector<double> finite_difference_jacobian(
    const std::function<std::vector<double>(const std::vector<double>&)>& g, const std::vector<double>& x,
    double relative_step = 1e-3) {
  const std::size_t n = x.size();
  std::vector<double> jacobian;
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double h = relative_step * std::max(1.0, std::abs(x[k]));
    // D(h) = (g(x + h) - g(x - h)) / 2h; (4 D(h/2) - D(h)) / 3 cancels the h^2 term.
    const auto central = [&](double step) {
      std::vector<double> plus = x, minus = x;
      plus[k] += step;
      minus[k] -= step;
      std::vector<double> a = g(plus);
      const std::vector<double> b = g(minus);
      for (std::size_t i = 0; i < a.size(); ++i) a[i] = (a[i] - b[i]) / (2 * step);
      return a;
    };
    const std::vector<double> coarse = central(h), fine = central(h / 2);
    if (k == 0) {
      m = coarse.size();
      jacobian.assign(m * n, 0.0);
    }
    for (std::size_t i = 0; i < m; ++i) jacobian[i * n + k] = (4 * fine[i] - coarse[i]) / 3;
  }
  return jacobian;
}

}  // namespace kanegen::numeric
