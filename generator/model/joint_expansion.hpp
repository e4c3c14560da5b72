// SPDX-License-Identifier: GPL-2.0-or-later
// Compound joint types (planar, free) as chains of primitive ones, as
// MuJoCo builds them: a joint of type planar named J between P and C
// becomes J_x (a slide along e1), J_y (a slide along e2) and J_theta (a
// turn about the axis n), with two massless frames J_x_frame and J_y_frame
// between them; a free joint J becomes J_x, J_y, J_z (slides along the
// joint frame's axes) and the spherical joint J, with frames J_x_frame,
// J_y_frame and J_z_frame. The loaders apply it before check_model, so that the
// checks, the symbolic stages and the numeric path see primitive joints
// only, and a coordinate of the compound joint is one of a step.
#pragma once

#include <array>

#include "model/model.hpp"

namespace kanegen::model {

/// The frame of a compound joint: e1 and e2 across the unit axis n, and n.
/// e1 is the coordinate axis least aligned with n (the first on a tie), made
/// normal to it, and e2 = n x e1; for n = z they are x and y.
std::array<std::array<double, 3>, 3> compound_joint_frame(const std::array<double, 3>& unit_axis);

/// Replaces every joint of a compound type by its steps (in its place in the
/// joint list, so the coordinates keep the file's order) and adds their
/// frames to the bodies. Throws ModelError at the joint for a name its steps
/// would take, for an axis of zero length, for what a joint of several
/// coordinates (compound or spherical) cannot carry (a spring, damping, a
/// prescribed motion, a node of a flexible parent, a loop in the model), and
/// at the output or joint force that names it instead of a step.
void expand_compound_joints(Model& model);

}  // namespace kanegen::model
