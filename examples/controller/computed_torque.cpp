// SPDX-License-Identifier: MIT
// Computed-torque control of the 7-DOF arm with the generated kernels:
// tau = M(q) (qdd_ref + Kd (qd_ref - u) + Kp (q_ref - q)) - f(q, u), integrated
// with the allocation-free RK4 step of the runtime. Prints the final tracking
// error; exits non-zero if the controller does not converge.
#include <kanegen/runtime/integrators.hpp>

#include <cmath>
#include <cstdio>

#include "arm7.hpp"

namespace arm = kanegen_models::arm7;

int main() {
  arm::Params params;
  constexpr int n = arm::NU;
  double x[2 * n] = {};  // q, u: start at rest in the zero pose
  const double q_ref[n] = {0.5, -0.3, 0.2, 0.8, -0.4, 0.3, 0.1};
  const double kp = 100.0, kd = 20.0;

  auto closed_loop = [&](double t, const double* state, double* xdot) {
    const double* q = state;
    const double* u = state + n;
    double m[n * n], f[n], zero[n] = {}, tau[n], a[n];
    arm::mass_matrix(params, q, m);
    arm::forcing(params, t, q, u, zero, f);
    for (int i = 0; i < n; ++i) a[i] = kp * (q_ref[i] - q[i]) - kd * u[i];
    for (int i = 0; i < n; ++i) {
      tau[i] = -f[i];
      for (int k = 0; k < n; ++k) tau[i] += m[i * n + k] * a[k];
    }
    arm::coordinate_rates(q, u, xdot);
    arm::forward_dynamics(params, t, q, u, tau, xdot + n);
  };

  const double h = 1e-3;
  for (int step = 0; step < 3000; ++step) kanegen::runtime::rk4_step<2 * n>(closed_loop, step * h, h, x);

  double error = 0;
  for (int i = 0; i < n; ++i) error = std::fmax(error, std::fabs(x[i] - q_ref[i]));
  std::printf("largest joint error after 3 s: %.3e rad\n", error);
  return error < 1e-3 ? 0 : 1;
}
