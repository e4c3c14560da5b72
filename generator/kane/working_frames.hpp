// SPDX-License-Identifier: GPL-2.0-or-later
// The frames the articulated-body recursion works in: per body, axes with its
// joint axis along z and an origin on that axis, turned about it and slid
// along it so that the constant part of the transform to the parent's frame
// is as sparse as Denavit-Hartenberg's (Khalil-Kleinfinger's form for trees):
//   x_parent = Rz(gamma) [ (a, 0, eps) + Rx(alpha) ( delta e_z + Rz(theta) x ) ],
// theta = theta0 + q (revolute), delta = delta0 + q (prismatic). Each body
// turns and slides its frame for its first child, so on a chain gamma = eps
// = 0: the transform is two turns about coordinate axes (one by a constant)
// and two shifts along one, where the body frames need a general rotation
// and a general offset.
#pragma once

#include <vector>

#include "kinematics/tree_kinematics.hpp"
#include "symbolic/program.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

/// x_outer = turn x_inner + shift (a turn about a coordinate axis, a shift
/// along one or two, or, where the frames are not constant, both general).
struct FrameStep {
  symbolic::Mat3 turn = symbolic::identity_mat();
  symbolic::Vec3 shift = symbolic::zero_vec();
  bool turns() const;   ///< turn is not the identity
  bool shifts() const;  ///< shift is not zero
};

struct WorkingFrame {
  /// From the body frame: x_working = turn x_body + shift (constant).
  FrameStep from_body;
  symbolic::Vec3 axis;  ///< the joint axis, working axes (e_z unless flexible or spherical)
  /// To the parent's working frame, the parent's side first (empty for a
  /// body on the ground: nothing passes to the ground and it does not move).
  std::vector<FrameStep> to_parent;

  /// Column c of the joint's S in working axes: the axis, or a spherical
  /// joint's child axis c (its working frame is its body frame).
  symbolic::Vec3 column(const kinematics::JointFrame& joint, int c) const {
    return joint.model.spherical() ? joint.column(c) : axis;
  }
};

/// Per body (TreeKinematics::bodies order). `flexible[i]`: body i has elastic
/// coordinates; its working frame is its body frame (its elastic terms and
/// its children's node partials are in those axes), as is a spherical
/// joint's child's (three axes of S, none to turn to e_z). A body whose joint is on
/// a node, or whose joint origin depends on parameters, gets one general step.
std::vector<WorkingFrame> working_frames(const kinematics::TreeKinematics& tree,
                                         const std::vector<bool>& flexible, symbolic::Program& program);

}  // namespace kanegen::kane
