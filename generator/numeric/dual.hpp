// Forward-mode automatic differentiation along one direction: a value and
// its derivative. Nesting (Dual<Dual<double>>) gives second derivatives.
// Only what the position functions need: + - * / with each other and with
// plain numbers, sin and cos.
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

}  // namespace kanegen::numeric
