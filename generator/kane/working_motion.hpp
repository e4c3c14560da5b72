// SPDX-License-Identifier: GPL-2.0-or-later
// The bodies' motion in the recursion's working frames (kane/working_frames.*):
// angular velocity and the rest accelerations (u_dot = 0; gravity is the
// ground's -g), carried outward through each joint's Khalil-Kleinfinger steps,
// so that a rigid body's inertia wrench is formed in its working axes, where
// its inertia is numbers, instead of in its body axes and turned per call.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "kane/working_frames.hpp"
#include "kinematics/tree_kinematics.hpp"
#include "symbolic/program.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

struct WorkingMotion {
  symbolic::Vec3 omega;       ///< angular velocity
  symbolic::Vec3 alpha_rest;  ///< angular acceleration with u_dot = 0
  symbolic::Vec3 accel_rest;  ///< acceleration of the working origin with u_dot = 0, gravity's -g in it
};

/// Per body (TreeKinematics::bodies order), in its working axes. A body
/// moves relative to its parent's working frame by its joint alone (a turn
/// about or a slide along its working axis), so its motion follows from its
/// parent's through the steps `to_parent`; a body on the ground, on a node of
/// a flexible parent, or flexible itself takes its body frame's motion
/// (TreeKinematics), moved to its working frame. `speeds`: u, by speed.
std::vector<WorkingMotion> working_motion(const kinematics::TreeKinematics& tree,
                                          const std::vector<WorkingFrame>& frames,
                                          const std::vector<bool>& flexible,
                                          const std::vector<GiNaC::ex>& speeds, symbolic::Program& program);

/// Accelerations without velocity terms (angular, and linear at the origin),
/// carried from a parent's working frame to a child's through its steps
/// (`WorkingFrame::to_parent`, parent's side first): a shift adds angular x
/// shift to the linear part, a turn turns both.
void carry_outward(const std::vector<FrameStep>& steps, symbolic::Vec3& angular, symbolic::Vec3& linear,
                   symbolic::Program& program);

/// A rigid body's inertia about its working origin, in working axes: mass,
/// first moment h = m c and second moment K.
struct WorkingInertia {
  GiNaC::ex mass;
  symbolic::Vec3 moment;
  symbolic::Mat3 second;
};

/// The inertia about the body origin in body axes (mass, h, K) moved to the
/// working frame (x_working = T x_body + s): numbers for a rigid body.
WorkingInertia working_inertia(const GiNaC::ex& mass, const symbolic::Vec3& moment,
                               const symbolic::Mat3& second, const FrameStep& from_body);

/// A wrench: a moment about a frame's origin and a force, in its axes.
struct SpatialForce {
  symbolic::Vec3 moment = symbolic::zero_vec(), force = symbolic::zero_vec();
};

/// A wrench about the body origin in body axes, about the working origin in working axes.
SpatialForce wrench_in_working(const SpatialForce& body_wrench, const FrameStep& from_body,
                               symbolic::Program& program);

/// The rate of momentum about the working origin of a rigid body with
/// angular velocity w, angular acceleration alpha and origin acceleration a:
/// (K alpha + h x a + w x K w, m a + alpha x h + w x (w x h)).
SpatialForce momentum_rate(const WorkingInertia& inertia, const symbolic::Vec3& omega,
                           const symbolic::Vec3& alpha, const symbolic::Vec3& accel,
                           symbolic::Program& program);

}  // namespace kanegen::kane
