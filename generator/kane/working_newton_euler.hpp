// SPDX-License-Identifier: GPL-2.0-or-later
// Newton and Euler's recursion on a rigid tree in the recursion's working
// frames (kane/working_frames.*): each joint adds a turn about or a slide
// along z, each step to the parent is a turn about or a shift along a
// coordinate axis, and each body's inertia is numbers there, so the inverse
// dynamics and the gravity forces cost about what the articulated-body
// recursion's outward pass and body wrenches do.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "kane/articulated_body.hpp"
#include "kinematics/tree_kinematics.hpp"
#include "symbolic/program.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

struct NewtonEuler {
  /// By speed: the bodies' share of M u_dot - f, i.e. the subtree's rate of
  /// momentum less its applied wrench, projected on the joint (the joints'
  /// own forces are not in it).
  std::vector<GiNaC::ex> inertial;
  /// By speed: g = dV_gravity/dq, minus the subtree's weight projected on the joint.
  std::vector<GiNaC::ex> gravity;
};

/// A rigid tree (no flexible body): `bodies` as for articulated_body_dynamics
/// (their inertias and applied wrenches; the rest accelerations come from
/// `tree`, gravity as the ground's -g in them), `speeds` u, `accelerations`
/// u_dot, `gravity` in world axes.
NewtonEuler working_newton_euler(const kinematics::TreeKinematics& tree, const std::vector<TreeBody>& bodies,
                                 const std::vector<GiNaC::ex>& speeds,
                                 const std::vector<GiNaC::ex>& accelerations, const symbolic::Vec3& gravity,
                                 symbolic::Program& program);

}  // namespace kanegen::kane
