// SPDX-License-Identifier: MIT
#include "arm7_tracking.hpp"

#include <math.h>

#include "arm7_float.hpp"
#include "kanegen/runtime/rk4.hpp"

namespace arm7_tracking {
namespace {

namespace model = kanegen_models::arm7_float;
constexpr int n = model::NU;

// The reference: each joint swings about an offset with its own amplitude
// and frequency, so that every joint moves and the arm's inertia changes.
constexpr float kOffset[n] = {0.0f, 0.6f, 0.0f, -1.2f, 0.0f, 0.8f, 0.0f};
constexpr float kAmplitude[n] = {0.5f, 0.3f, 0.4f, 0.3f, 0.5f, 0.4f, 0.6f};
constexpr float kOmega[n] = {1.1f, 1.3f, 1.7f, 1.9f, 2.3f, 2.9f, 3.1f};  // rad/s

void reference(float t, float* q, float* u, float* a) {
  for (int i = 0; i < n; ++i) {
    const float s = sinf(kOmega[i] * t), c = cosf(kOmega[i] * t);
    q[i] = kOffset[i] + kAmplitude[i] * s;
    u[i] = kAmplitude[i] * kOmega[i] * c;
    a[i] = -kAmplitude[i] * kOmega[i] * kOmega[i] * s;
  }
}

/// Computed torque: tau = M(q) (a_ref + Kd (u_ref - u) + Kp (q_ref - q)) - f(q, u, 0),
/// since M udot = f(q, u, 0) + tau for joint torques. That is the generated
/// inverse_dynamics at the commanded acceleration: Newton and Euler's
/// recursion, O(n), without forming M. Gains for a critically damped error
/// of 10 rad/s.
void control(const model::Params& p, float t, const float* q, const float* u, float* tau) {
  constexpr float kp = 100.0f, kd = 20.0f;
  float q_ref[n], u_ref[n], a_ref[n], a[n];
  reference(t, q_ref, u_ref, a_ref);
  for (int i = 0; i < n; ++i) a[i] = a_ref[i] + kd * (u_ref[i] - u[i]) + kp * (q_ref[i] - q[i]);
  model::inverse_dynamics(p, t, q, u, a, tau);
}

}  // namespace

Result run(int steps, float h, const Hooks& hooks) {
  const model::Params p;
  Result result;
  float x[2 * n], q_ref[n], u_ref[n], a_ref[n], tau[n];
  reference(0.0f, q_ref, u_ref, a_ref);
  for (int i = 0; i < n; ++i) {
    x[i] = q_ref[i] + 0.05f;  // start off the reference, to see the error decay
    x[n + i] = 0.0f;
  }
  for (int k = 0; k < steps; ++k) {
    const float t = static_cast<float>(k) * h;
    if (hooks.before_control) hooks.before_control();
    control(p, t, x, x + n, tau);
    if (hooks.after_control) hooks.after_control();
    const auto plant = [&](float ts, const float* s, float* sdot) {
      for (int i = 0; i < n; ++i) sdot[i] = s[n + i];  // q_dot = u for revolute joints
      if (model::forward_dynamics(p, ts, s, s + n, tau, sdot + n) != 0) ++result.failed_steps;
    };
    kanegen::runtime::rk4_step<2 * n>(plant, t, h, x);
    reference(static_cast<float>(k + 1) * h, q_ref, u_ref, a_ref);
    float squares = 0.0f;
    for (int i = 0; i < n; ++i) {
      const float e = q_ref[i] - x[i];
      squares += e * e;
      if (2 * (k + 1) > steps && fabsf(e) > result.max_error) result.max_error = fabsf(e);
    }
    result.final_error = sqrtf(squares / n);
  }
  result.steps = steps;
  return result;
}

}  // namespace arm7_tracking
