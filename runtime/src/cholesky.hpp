// SPDX-License-Identifier: MIT
// The dense Cholesky factorization the runtime uses for mass matrices and
// for the Gram matrices C M^-1 C^T of the loop equations, in place on
// row-major storage, allocating nothing. Private to the runtime library
// (templates/solve_saddle.hpp has the generated code's own).
#pragma once

#include <cmath>

namespace kanegen::runtime::detail {

/// In place, the lower Cholesky factor L (L L^T = A) of the symmetric m x m
/// row-major A (lower triangle read). Without `used`: false if A is not
/// positive definite. With `used`: a row whose pivot falls to `drop` times
/// its diagonal or below (a combination of earlier rows: dependent loop
/// equations) is skipped, used[j] = 0, and the factorization goes on.
inline bool cholesky_factor(double* A, int m, char* used = nullptr, double drop = 0.0) {
  for (int j = 0; j < m; ++j) {
    const double diagonal = A[j * m + j];
    double s = diagonal;
    for (int k = 0; k < j; ++k)
      if (!used || used[k]) s -= A[j * m + k] * A[j * m + k];
    const bool ok = s > drop * diagonal && diagonal > 0.0;
    if (used) used[j] = ok;
    if (!ok) {
      if (used) continue;
      return false;
    }
    const double l = std::sqrt(s);
    A[j * m + j] = l;
    for (int i = j + 1; i < m; ++i) {
      double v = A[i * m + j];
      for (int k = 0; k < j; ++k)
        if (!used || used[k]) v -= A[i * m + k] * A[j * m + k];
      A[i * m + j] = v / l;
    }
  }
  return true;
}

/// x := (L L^T)^-1 x with L from cholesky_factor; the skipped rows get 0.
inline void cholesky_solve(const double* L, int m, double* x, const char* used = nullptr) {
  for (int i = 0; i < m; ++i) {
    if (used && !used[i]) {
      x[i] = 0.0;
      continue;
    }
    for (int k = 0; k < i; ++k)
      if (!used || used[k]) x[i] -= L[i * m + k] * x[k];
    x[i] /= L[i * m + i];
  }
  for (int i = m - 1; i >= 0; --i) {
    if (used && !used[i]) continue;
    for (int k = i + 1; k < m; ++k)
      if (!used || used[k]) x[i] -= L[k * m + i] * x[k];
    x[i] /= L[i * m + i];
  }
}

/// A row of a Gram matrix C M^-1 C^T whose Cholesky pivot falls to this
/// fraction of its diagonal is taken as dependent on the earlier ones.
inline constexpr double kDependentRow = 1e-12;

/// The Gram matrix G (nc x nc, lower triangle) of the loop equations
/// factored in place, dependent rows dropped (used[i] = 0): the
/// pseudo-inverse G^+ the least-norm corrections apply with
/// cholesky_solve(G, nc, x, used). False if no row is kept.
inline bool factor_gram(double* G, int nc, char* used) {
  cholesky_factor(G, nc, used, kDependentRow);
  for (int i = 0; i < nc; ++i)
    if (used[i]) return true;
  return false;
}

}  // namespace kanegen::runtime::detail
