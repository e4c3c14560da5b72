// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/working_motion.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

/// The body frame's motion at the working origin, in working axes: with
/// x_working = T x_body + s the working origin is at -T^T s in body
/// coordinates, so a = T a_body - alpha x s - omega x (omega x s).
WorkingMotion from_body(const kinematics::BodyState& b, const FrameStep& step, Program& program) {
  WorkingMotion m;
  m.omega = named(program, mul(step.turn, b.omega));
  m.alpha_rest = named(program, mul(step.turn, b.alpha_rest));
  m.accel_rest = named(program, mul(step.turn, b.accel_rest));
  if (step.shifts()) {
    const Vec3 spin = named(program, cross(m.omega, step.shift));
    m.accel_rest = named(program, m.accel_rest - cross(m.alpha_rest, step.shift) - cross(m.omega, spin));
  }
  return m;
}

}  // namespace

void carry_outward(const std::vector<FrameStep>& steps, Vec3& angular, Vec3& linear, Program& program) {
  for (const FrameStep& step : steps) {
    if (step.shifts()) linear = named(program, linear + cross(angular, step.shift));
    if (!step.turns()) continue;
    angular = named(program, mul_transposed(step.turn, angular));
    linear = named(program, mul_transposed(step.turn, linear));
  }
}

WorkingInertia working_inertia(const GiNaC::ex& mass, const Vec3& moment, const Mat3& second,
                               const FrameStep& from_body) {
  const Mat3& t = from_body.turn;
  const Vec3 h = mul(t, moment);
  const Mat3 k = mul(t, mul(second, transpose(t)));
  // About the working origin, from which the body origin is at r = s:
  // sum of m (|r + x|^2 1 - (r + x)(r + x)^T) over the body's points x.
  const Vec3& r = from_body.shift;
  WorkingInertia w{mass, h + mass * r, Mat3{}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      w.second[3 * i + j] = k[3 * i + j] + (i == j ? mass * dot(r, r) + 2 * dot(r, h) : GiNaC::ex(0)) -
                            mass * r[i] * r[j] - r[i] * h[j] - h[i] * r[j];
  return w;
}

SpatialForce wrench_in_working(const SpatialForce& body_wrench, const FrameStep& from_body,
                               Program& program) {
  const Vec3 force = named(program, mul(from_body.turn, body_wrench.force));
  return {named(program, mul(from_body.turn, body_wrench.moment) + cross(from_body.shift, force)), force};
}

SpatialForce momentum_rate(const WorkingInertia& inertia, const Vec3& omega, const Vec3& alpha,
                           const Vec3& accel, Program& program) {
  const Vec3& h = inertia.moment;
  const Vec3 spin = named(program, mul(inertia.second, omega));
  const Vec3 whirl = named(program, cross(omega, h));
  return {mul(inertia.second, alpha) + cross(h, accel) + cross(omega, spin),
          inertia.mass * accel + cross(alpha, h) + cross(omega, whirl)};
}

std::vector<WorkingMotion> working_motion(const kinematics::TreeKinematics& tree,
                                          const std::vector<WorkingFrame>& frames,
                                          const std::vector<bool>& flexible,
                                          const std::vector<GiNaC::ex>& speeds, Program& program) {
  const auto& states = tree.bodies();
  std::vector<WorkingMotion> out(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    if (state.parent_state < 0 || joint.on_node || flexible[i]) {
      out[i] = from_body(state, frames[i].from_body, program);
      continue;
    }
    // Outward through the steps, parent's side first (x_outer = turn x_inner + shift).
    WorkingMotion m = out[state.parent_state];
    for (const FrameStep& step : frames[i].to_parent) {
      if (step.shifts()) {
        const Vec3 spin = named(program, cross(m.omega, step.shift));
        m.accel_rest = named(program, m.accel_rest + cross(m.alpha_rest, step.shift) + cross(m.omega, spin));
      }
      if (!step.turns()) continue;
      m.omega = named(program, mul_transposed(step.turn, m.omega));
      m.alpha_rest = named(program, mul_transposed(step.turn, m.alpha_rest));
      m.accel_rest = named(program, mul_transposed(step.turn, m.accel_rest));
    }
    // The joint's own motion: a turn about the working axis, or a slide
    // along it (the slide's Coriolis term 2 omega x u a).
    // A spherical joint's three turns all meet the omega carried in.
    const Vec3 carried = m.omega;
    for (int c = 0; c < joint.speeds(); ++c) {
      const GiNaC::ex& u = speeds[joint.speed + c];
      const Vec3 axis = frames[i].column(joint, c);
      if (joint.model.slides()) {
        m.accel_rest = named(program, m.accel_rest + 2 * u * cross(m.omega, axis));
      } else if (joint.model.turns()) {
        m.alpha_rest = named(program, m.alpha_rest + u * cross(carried, axis));
        m.omega = named(program, m.omega + u * axis);
      }
    }
    out[i] = m;
  }
  return out;
}

}  // namespace kanegen::kane
