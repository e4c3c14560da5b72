// SPDX-License-Identifier: GPL-2.0-or-later
// Gauss-Legendre quadrature on [0, 1]. The element integrals of the
// finite-element layer (mass, inertia invariants, geometric stiffness) are
// polynomials in the natural coordinate, so a rule with n points integrates
// them exactly when their degree is at most 2 n - 1.
#pragma once

#include <vector>

namespace kanegen::fem {

struct QuadratureRule {
  std::vector<double> points;   ///< n, in (0, 1), ascending
  std::vector<double> weights;  ///< n, positive, summing to 1
};

/// The n-point Gauss-Legendre rule on [0, 1] (n >= 1), exact for polynomials
/// of degree <= 2 n - 1; nodes by Newton's method on the Legendre polynomial.
QuadratureRule gauss_legendre(int n);

/// The fewest Gauss points that integrate a polynomial of this degree exactly.
inline int gauss_points_for_degree(int degree) { return degree / 2 + 1; }

}  // namespace kanegen::fem
