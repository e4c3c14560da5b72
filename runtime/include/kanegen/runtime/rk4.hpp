// SPDX-License-Identifier: MIT
// Classical RK4 steps that allocate nothing, throw nothing and include
// nothing, so a generated model can be stepped on an embedded target. Real
// is double, or float with the kernels of `kanegen generate --precision
// float` (every constant is a Real, so a float step never touches double).
#pragma once

namespace kanegen::runtime {

/// One classical RK4 step of size h from (t, x), in place. `rhs(t, x, xdot)`
/// evaluates the derivative (its return value, if any, is ignored).
/// `work` must hold 5*n Reals; nothing is allocated.
template <class Real, class F>
void rk4_step(F&& rhs, Real t, Real h, Real* x, int n, Real* work) {
  Real* k1 = work;
  Real* k2 = work + n;
  Real* k3 = work + 2 * n;
  Real* k4 = work + 3 * n;
  Real* xt = work + 4 * n;
  const Real half = Real(0.5) * h;
  rhs(t, static_cast<const Real*>(x), k1);
  for (int i = 0; i < n; ++i) xt[i] = x[i] + half * k1[i];
  rhs(t + half, static_cast<const Real*>(xt), k2);
  for (int i = 0; i < n; ++i) xt[i] = x[i] + half * k2[i];
  rhs(t + half, static_cast<const Real*>(xt), k3);
  for (int i = 0; i < n; ++i) xt[i] = x[i] + h * k3[i];
  rhs(t + h, static_cast<const Real*>(xt), k4);
  const Real sixth = h / Real(6);
  for (int i = 0; i < n; ++i) x[i] += sixth * (k1[i] + Real(2) * (k2[i] + k3[i]) + k4[i]);
}

/// Fixed-size RK4 step for a state of N Reals: workspace on the stack.
template <int N, class Real, class F>
void rk4_step(F&& rhs, Real t, Real h, Real* x) {
  static_assert(N > 0, "state size must be positive");
  Real work[5 * N];
  rk4_step(rhs, t, h, x, N, work);
}

}  // namespace kanegen::runtime
