// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/working_newton_euler.hpp"

#include "kane/working_frames.hpp"
#include "kane/working_motion.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
using GiNaC::ex;
namespace {

/// A wrench about the inner frame's origin in its axes, about the outer
/// one's in its axes, through the steps from inner to outer (parent's side first).
SpatialForce to_parent(const SpatialForce& w, const std::vector<FrameStep>& steps, Program& program) {
  SpatialForce x = w;
  for (std::size_t k = steps.size(); k-- > 0;) {
    const FrameStep& step = steps[k];
    if (step.turns()) x = {named(program, mul(step.turn, x.moment)), named(program, mul(step.turn, x.force))};
    if (step.shifts()) x.moment = named(program, x.moment + cross(step.shift, x.force));
  }
  return x;
}

ex projected(const kinematics::JointFrame& joint, const Vec3& axis, const SpatialForce& w) {
  return joint.model.force_of(axis, w.moment, w.force);
}

}  // namespace

NewtonEuler working_newton_euler(const kinematics::TreeKinematics& tree, const std::vector<TreeBody>& bodies,
                                 const std::vector<ex>& speeds, const std::vector<ex>& accelerations,
                                 const Vec3& gravity, Program& program) {
  const auto& states = tree.bodies();
  const std::size_t count = states.size();
  const std::vector<bool> flexible(count, false);
  const std::vector<WorkingFrame> frames = working_frames(tree, flexible, program);
  const std::vector<WorkingMotion> motion = working_motion(tree, frames, flexible, speeds, program);

  // Outward: the accelerations that u_dot gives, and gravity, in working axes.
  std::vector<Vec3> alpha(count), accel(count), weight_field(count);
  for (std::size_t i = 0; i < count; ++i) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    const WorkingFrame& frame = frames[i];
    Vec3 angular = zero_vec(), linear = zero_vec(), g;
    if (state.parent_state < 0) {
      g = named(program, mul(frame.from_body.turn, mul_transposed(state.rotation, gravity)));
    } else {
      angular = alpha[state.parent_state];
      linear = accel[state.parent_state];
      g = weight_field[state.parent_state];
      carry_outward(frame.to_parent, angular, linear, program);
      for (const FrameStep& step : frame.to_parent)
        if (step.turns()) g = named(program, mul_transposed(step.turn, g));
    }
    for (int c = 0; c < joint.speeds(); ++c) {
      const ex& udot = accelerations[joint.speed + c];
      Vec3& moved = joint.model.part(angular, linear);  // a_i += S u_dot
      moved = named(program, moved + udot * frame.column(joint, c));
    }
    alpha[i] = angular;
    accel[i] = linear;
    weight_field[i] = g;
  }

  // Each body's rate of momentum less its applied wrench, and its weight
  // (h x g, m g); inward, the subtree sums, projected on each joint.
  std::vector<SpatialForce> inertial(count), weight(count);
  for (std::size_t i = 0; i < count; ++i) {
    const TreeBody& body = bodies[i];
    const FrameStep& from_body = frames[i].from_body;
    const WorkingInertia inertia = working_inertia(body.mass, body.moment, body.second, from_body);
    const SpatialForce applied =
        wrench_in_working({body.applied_moment, body.applied_force}, from_body, program);
    const WorkingMotion& m = motion[i];
    const SpatialForce rate =
        momentum_rate(inertia, m.omega, m.alpha_rest + alpha[i], m.accel_rest + accel[i], program);
    inertial[i] = {rate.moment - applied.moment, rate.force - applied.force};
    weight[i] = {cross(inertia.moment, weight_field[i]), inertia.mass * weight_field[i]};
  }
  NewtonEuler out{std::vector<ex>(speeds.size(), 0), std::vector<ex>(speeds.size(), 0)};
  for (std::size_t i = count; i-- > 0;) {
    inertial[i] = {named(program, inertial[i].moment), named(program, inertial[i].force)};
    weight[i] = {named(program, weight[i].moment), named(program, weight[i].force)};
    const kinematics::JointFrame& joint = tree.joints()[states[i].joint];
    for (int c = 0; c < joint.speeds(); ++c) {
      out.inertial[joint.speed + c] = projected(joint, frames[i].column(joint, c), inertial[i]);
      out.gravity[joint.speed + c] = -projected(joint, frames[i].column(joint, c), weight[i]);
    }
    const int parent = states[i].parent_state;
    if (parent < 0) continue;
    for (auto [sums, own] : {std::pair{&inertial, &inertial[i]}, std::pair{&weight, &weight[i]}}) {
      const SpatialForce up = to_parent(*own, frames[i].to_parent, program);
      SpatialForce& p = (*sums)[parent];
      p = {p.moment + up.moment, p.force + up.force};
    }
  }
  return out;
}

}  // namespace kanegen::kane
