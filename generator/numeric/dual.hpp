// SPDX-License-Identifier: GPL-2.0-or-later
// Forward-mode automatic differentiation along one direction: a value and
// its derivative. Nesting (Dual<Dual<double>>) gives second derivatives.
// Only what the position functions and the prescribed motions need: + - * /
// with each other and with plain numbers, sin, cos, tan, sqrt, exp, log and
// powers.
#pragma once

#include <cmath>

namespace kanegen::numeric {

template <class T>
struct Dual {
  T v{};  ///< value
  T d{};  ///< derivative along the seeded direction

  Dual() = default;
  Dual(const T& value, const T& derivative) : v(value), d(derivative) {}
  /// A constant (derivative zero).
  explicit Dual(double value) : v(value), d(0.0) {}
};

template <class T>
Dual<T> operator+(const Dual<T>& a, const Dual<T>& b) {
  return {a.v + b.v, a.d + b.d};
}
template <class T>
Dual<T> operator-(const Dual<T>& a, const Dual<T>& b) {
  return {a.v - b.v, a.d - b.d};
}
template <class T>
Dual<T> operator-(const Dual<T>& a) {
  return {-a.v, -a.d};
}
template <class T>
Dual<T> operator*(const Dual<T>& a, const Dual<T>& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d};
}
template <class T>
Dual<T> operator/(const Dual<T>& a, const Dual<T>& b) {
  const T value = a.v / b.v;
  return {value, (a.d - value * b.d) / b.v};
}

// Mixed with plain numbers (the model's constants).
template <class T>
Dual<T> operator+(const Dual<T>& a, double s) {
  return {a.v + s, a.d};
}
template <class T>
Dual<T> operator+(double s, const Dual<T>& a) {
  return {s + a.v, a.d};
}
template <class T>
Dual<T> operator-(const Dual<T>& a, double s) {
  return {a.v - s, a.d};
}
template <class T>
Dual<T> operator-(double s, const Dual<T>& a) {
  return {s - a.v, -a.d};
}
template <class T>
Dual<T> operator*(const Dual<T>& a, double s) {
  return {a.v * s, a.d * s};
}
template <class T>
Dual<T> operator*(double s, const Dual<T>& a) {
  return {s * a.v, s * a.d};
}
template <class T>
Dual<T> operator/(const Dual<T>& a, double s) {
  return {a.v / s, a.d / s};
}

template <class T>
Dual<T>& operator+=(Dual<T>& a, const Dual<T>& b) {
  return a = a + b;
}
template <class T>
Dual<T>& operator-=(Dual<T>& a, const Dual<T>& b) {
  return a = a - b;
}

template <class T>
Dual<T> sin(const Dual<T>& x) {
  using std::cos;
  using std::sin;
  return {sin(x.v), cos(x.v) * x.d};
}
template <class T>
Dual<T> cos(const Dual<T>& x) {
  using std::cos;
  using std::sin;
  return {cos(x.v), -(sin(x.v) * x.d)};
}

template <class T>
Dual<T> tan(const Dual<T>& x) {
  using std::cos;
  using std::tan;
  const T c = cos(x.v);
  return {tan(x.v), x.d / (c * c)};
}
template <class T>
Dual<T> sqrt(const Dual<T>& x) {
  using std::sqrt;
  const T root = sqrt(x.v);
  return {root, x.d / (2.0 * root)};
}
template <class T>
Dual<T> exp(const Dual<T>& x) {
  using std::exp;
  const T e = exp(x.v);
  return {e, e * x.d};
}
template <class T>
Dual<T> log(const Dual<T>& x) {
  using std::log;
  return {log(x.v), x.d / x.v};
}
/// x^c for a constant exponent (any sign of x when c is an integer).
template <class T>
Dual<T> pow(const Dual<T>& x, double c) {
  using std::pow;
  if (c == 0.0) return Dual<T>(1.0);
  return {pow(x.v, c), c * pow(x.v, c - 1.0) * x.d};
}
/// x^y with a varying exponent: exp(y log x), x > 0.
template <class T>
Dual<T> pow(const Dual<T>& x, const Dual<T>& y) {
  return exp(y * log(x));
}

/// The value at the bottom of a nesting of duals.
inline double value_of(double x) { return x; }
template <class T>
double value_of(const Dual<T>& x) {
  return value_of(x.v);
}

}  // namespace kanegen::numeric
