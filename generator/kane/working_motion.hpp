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

}  // namespace kanegen::kane
