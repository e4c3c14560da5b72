// SPDX-License-Identifier: MIT
// Classical RK4 steps that allocate nothing, throw nothing and include
// nothing, so a generated model can be stepped on an embedded target.
#pragma once

namespace kanegen::runtime {

/// One classical RK4 step of size h from (t, x), in place. `rhs(t, x, xdot)`
/// evaluates the derivative (its return value, if any, is ignored).
/// `work` must hold 5*n doubles; nothing is allocated.
template <class F>
void rk4_step(F&& rhs, double t, double h, double* x, int n, double* work) {
  double* k1 = work;
  double* k2 = work + n;
  double* k3 = work + 2 * n;
  double* k4 = work + 3 * n;
  double* xt = work + 4 * n;
  const double half = 0.5 * h;
  rhs(t, static_cast<const double*>(x), k1);
  for (int i = 0; i < n; ++i) xt[i] = x[i] + half * k1[i];
  rhs(t + half, static_cast<const double*>(xt), k2);
  for (int i = 0; i < n; ++i) xt[i] = x[i] + half * k2[i];
  rhs(t + half, static_cast<const double*>(xt), k3);
  for (int i = 0; i < n; ++i) xt[i] = x[i] + h * k3[i];
  rhs(t + h, static_cast<const double*>(xt), k4);
  const double sixth = h / 6.0;
  for (int i = 0; i < n; ++i) x[i] += sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
}

/// Fixed-size RK4 step for a state of N doubles: workspace on the stack.
template <int N, class F>
void rk4_step(F&& rhs, double t, double h, double* x) {
  static_assert(N > 0, "state size must be positive");
  double work[5 * N];
  rk4_step(rhs, t, h, x, N, work);
}

}  // namespace kanegen::runtime
