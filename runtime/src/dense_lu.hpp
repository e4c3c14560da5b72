// SPDX-License-Identifier: MIT
// Dense LU factorization with partial pivoting, in place on preallocated
// row-major storage, for real and complex matrices (Radau's two iteration
// matrices). Private to the runtime library. Complex products are written
// out: std::complex's operator* checks for NaN and infinities through a
// library call (C99 Annex G) in the innermost loop.
#pragma once

#include <cmath>
#include <complex>
#include <utility>

namespace kanegen::runtime::detail {

inline double magnitude(double a) { return std::abs(a); }
inline double magnitude(const std::complex<double>& a) { return std::abs(a.real()) + std::abs(a.imag()); }

inline double times(double a, double b) { return a * b; }
inline std::complex<double> times(const std::complex<double>& a, const std::complex<double>& b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

inline double reciprocal(double a) { return 1.0 / a; }
inline std::complex<double> reciprocal(const std::complex<double>& a) {
  const double d = a.real() * a.real() + a.imag() * a.imag();
  return {a.real() / d, -a.imag() / d};
}

/// A := P A = L U in place (unit lower L below the diagonal, U on and above
/// it, row-major n x n); the diagonal of U holds its reciprocals. False if a
/// pivot is exactly zero or not finite (singular).
template <class T>
bool lu_factor_in_place(T* A, int n, int* pivots) {
  for (int k = 0; k < n; ++k) {
    int p = k;
    double best = magnitude(A[k * n + k]);
    for (int i = k + 1; i < n; ++i) {
      const double v = magnitude(A[i * n + k]);
      if (v > best) {
        best = v;
        p = i;
      }
    }
    if (!(best > 0.0) || !std::isfinite(best)) return false;
    pivots[k] = p;
    if (p != k)
      for (int j = 0; j < n; ++j) std::swap(A[k * n + j], A[p * n + j]);
    const T inverse = reciprocal(A[k * n + k]);
    A[k * n + k] = inverse;
    const T* row_k = &A[k * n];
    for (int i = k + 1; i < n; ++i) {
      T* row = &A[i * n];
      const T l = times(row[k], inverse);
      row[k] = l;
      for (int j = k + 1; j < n; ++j) row[j] -= times(l, row_k[j]);
    }
  }
  return true;
}

/// b := A^-1 b from the factors of lu_factor_in_place.
template <class T>
void lu_solve_in_place(const T* LU, int n, const int* pivots, T* b) {
  for (int k = 0; k < n; ++k) std::swap(b[k], b[pivots[k]]);
  for (int i = 1; i < n; ++i) {
    const T* row = &LU[i * n];
    T s = b[i];
    for (int j = 0; j < i; ++j) s -= times(row[j], b[j]);
    b[i] = s;
  }
  for (int i = n - 1; i >= 0; --i) {
    const T* row = &LU[i * n];
    T s = b[i];
    for (int j = i + 1; j < n; ++j) s -= times(row[j], b[j]);
    b[i] = times(s, row[i]);
  }
}

}  // namespace kanegen::runtime::detail
