// SPDX-License-Identifier: MIT
// LU factors and a matrix-vector product that skip the zeros outside each
// column's (or row's) nonzero range: the iteration matrices and mass
// matrices of finite-element models are banded by the element
// connectivity, and a dense 31 x 31 substitution spent most of its work on
// zeros. Skipping an exact zero changes no result (x - 0 y == x for finite
// y). Private to the runtime library; everything works in place on the
// caller's storage.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace kanegen::runtime::detail {

/// In-place LU with partial pivoting of the n x n row-major A. False if a
/// pivot is zero or below n eps of the largest entry (singular to working
/// precision), with its column in *column.
inline bool lu_factor(double* A, int n, int* pivots, int* column) {
  double largest = 0.0;
  for (int i = 0; i < n * n; ++i) largest = std::max(largest, std::abs(A[i]));
  const double tiny = n * std::numeric_limits<double>::epsilon() * largest;
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A[i * n + k]) > std::abs(A[p * n + k])) p = i;
    pivots[k] = p;
    if (!(std::abs(A[p * n + k]) > tiny)) {
      *column = k;
      return false;
    }
    if (p != k)
      for (int j = 0; j < n; ++j) std::swap(A[k * n + j], A[p * n + j]);
    const double inv = 1.0 / A[k * n + k];
    for (int i = k + 1; i < n; ++i) {
      const double l = A[i * n + k] *= inv;
      if (l == 0.0) continue;
      for (int j = k + 1; j < n; ++j) A[i * n + j] -= l * A[k * n + j];
    }
  }
  return true;
}

/// The factors LU of lu_factor (n x n row-major) as envelope_lu_solve
/// takes them: transposed into LUt (column k of L and U in row k), the
/// diagonal of U as its reciprocals (a division on the back substitution's
/// critical path costs several multiplications), and each column's nonzero
/// range: the first nonzero of U above the diagonal (k if none) and one past
/// the last nonzero of L below it (k + 1 if none).
inline void prepare_solve(const double* LU, int n, double* LUt, int* upper_begin, int* lower_end) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) LUt[j * n + i] = LU[i * n + j];
  for (int k = 0; k < n; ++k) {
    double* column = &LUt[k * n];
    column[k] = 1.0 / column[k];
    int begin = 0, end = n;
    while (begin < k && column[begin] == 0.0) ++begin;
    while (end > k + 1 && column[end - 1] == 0.0) --end;
    upper_begin[k] = begin;
    lower_end[k] = end;
  }
}

/// b := A^-1 b from the factors of prepare_solve: the substitutions run
/// down contiguous columns of L and U with independent updates, which
/// vectorize, within the columns' nonzero ranges. The factorization's row swaps moved whole rows,
/// multipliers included, so all of them apply to b before the forward
/// substitution.
inline void envelope_lu_solve(const double* LUt, int n, const int* pivots, const int* upper_begin,
                              const int* lower_end, double* b) {
  for (int k = 0; k < n; ++k)
    if (pivots[k] != k) std::swap(b[k], b[pivots[k]]);  // rare for the diagonally dominant ones
  for (int k = 0; k < n; ++k) {
    const double* column = &LUt[k * n];
    const double bk = b[k];
    for (int i = k + 1; i < lower_end[k]; ++i) b[i] -= column[i] * bk;
  }
  for (int k = n - 1; k >= 0; --k) {
    const double* column = &LUt[k * n];
    const double bk = b[k] *= column[k];
    for (int i = upper_begin[k]; i < k; ++i) b[i] -= column[i] * bk;
  }
}

/// The nonzero range [begin[i], end[i]) of each row of the n x n row-major A.
inline void row_envelopes(const double* A, int n, int* begin, int* end) {
  for (int i = 0; i < n; ++i) {
    const double* row = &A[i * n];
    int b = 0, e = n;
    while (b < n && row[b] == 0.0) ++b;
    while (e > b && row[e - 1] == 0.0) --e;
    begin[i] = b;
    end[i] = e;
  }
}

/// y := A x within the ranges of row_envelopes (y and x distinct).
inline void envelope_multiply(const double* A, int n, const int* begin, const int* end, const double* x,
                              double* y) {
  for (int i = 0; i < n; ++i) {
    const double* row = &A[i * n];
    double s = 0.0;
    for (int j = begin[i]; j < end[i]; ++j) s += row[j] * x[j];
    y[i] = s;
  }
}

}  // namespace kanegen::runtime::detail
