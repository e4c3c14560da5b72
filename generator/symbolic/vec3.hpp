// SPDX-License-Identifier: GPL-2.0-or-later
// Small 3-vector and 3x3-matrix algebra over GiNaC expressions, with a
// `named` step that files every component as an intermediate of the Program.
#pragma once

#include <ginac/ginac.h>

#include <array>

#include "symbolic/program.hpp"

namespace kanegen::symbolic {

using Vec3 = std::array<GiNaC::ex, 3>;
using Mat3 = std::array<GiNaC::ex, 9>;  ///< row-major

inline Vec3 zero_vec() { return {0, 0, 0}; }
inline Mat3 identity_mat() { return {1, 0, 0, 0, 1, 0, 0, 0, 1}; }

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(const GiNaC::ex& s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }

inline GiNaC::ex dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Vec3 mul(const Mat3& m, const Vec3& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}
inline Mat3 mul(const Mat3& a, const Mat3& b) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return c;
}

inline Mat3 transpose(const Mat3& m) { return {m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]}; }
/// m^T v without forming the transpose.
inline Vec3 mul_transposed(const Mat3& m, const Vec3& v) {
  return {m[0] * v[0] + m[3] * v[1] + m[6] * v[2], m[1] * v[0] + m[4] * v[1] + m[7] * v[2],
          m[2] * v[0] + m[5] * v[1] + m[8] * v[2]};
}

inline Vec3 named(Program& program, const Vec3& v) {
  return {program.define(v[0]), program.define(v[1]), program.define(v[2])};
}
inline Mat3 named(Program& program, const Mat3& m) {
  Mat3 r;
  for (int i = 0; i < 9; ++i) r[i] = program.define(m[i]);
  return r;
}

}  // namespace kanegen::symbolic
