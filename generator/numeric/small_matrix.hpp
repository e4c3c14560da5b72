// SPDX-License-Identifier: GPL-2.0-or-later
// 3-vectors and 3x3 matrices over any scalar type (double or Dual), so that
// the position functions are written once and differentiated by evaluation.
#pragma once

#include <array>

namespace kanegen::numeric {

template <class S>
using Vec = std::array<S, 3>;
/// Row-major.
template <class S>
using Mat = std::array<S, 9>;

template <class S>
Mat<S> identity() {
  Mat<S> m{};
  for (int i = 0; i < 9; ++i) m[i] = S(i % 4 == 0 ? 1.0 : 0.0);
  return m;
}

/// Element type conversion (double constants into a Dual computation).
template <class S, class T>
Vec<S> cast(const Vec<T>& a) {
  return {S(a[0]), S(a[1]), S(a[2])};
}

template <class A, class B>
auto add(const Vec<A>& a, const Vec<B>& b) -> Vec<decltype(a[0] + b[0])> {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
template <class A, class B>
auto sub(const Vec<A>& a, const Vec<B>& b) -> Vec<decltype(a[0] - b[0])> {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class S>
Vec<S> scale(const Vec<S>& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
template <class A, class B>
auto dot(const Vec<A>& a, const Vec<B>& b) -> decltype(a[0] * b[0]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class A, class B>
auto cross(const Vec<A>& a, const Vec<B>& b) -> Vec<decltype(a[0] * b[0])> {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <class A, class B>
auto mul(const Mat<A>& m, const Vec<B>& v) -> Vec<decltype(m[0] * v[0])> {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}
template <class A, class B>
auto mul(const Mat<A>& a, const Mat<B>& b) -> Mat<decltype(a[0] * b[0])> {
  Mat<decltype(a[0] * b[0])> c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return c;
}
template <class S>
Mat<S> transpose(const Mat<S>& m) {
  return {m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]};
}
template <class S>
Mat<S> sub(const Mat<S>& a, const Mat<S>& b) {
  Mat<S> c;
  for (int i = 0; i < 9; ++i) c[i] = a[i] - b[i];
  return c;
}

/// The vector w of a skew-symmetric W (W x = w x x), from its antisymmetric
/// part so that round-off in W's symmetric part does not leak in.
inline Vec<double> vee(const Mat<double>& w) {
  return {0.5 * (w[7] - w[5]), 0.5 * (w[2] - w[6]), 0.5 * (w[3] - w[1])};
}

}  // namespace kanegen::numeric
