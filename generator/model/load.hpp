// SPDX-License-Identifier: GPL-2.0-or-later
// Entry point of the model stage: a .json or .urdf file becomes a checked Model.
#pragma once

#include <array>
#include <string>

#include "model/model.hpp"
#include "model/model_error.hpp"

namespace kanegen::model {

struct LoadOptions {
  /// URDF has no gravity; ROS convention is 9.81 m/s^2 along -z.
  std::array<double, 3> urdf_gravity{0.0, 0.0, -9.81};
  /// Read <dynamics damping> of URDF joints as viscous joint damping
  /// (friction is ignored either way).
  bool urdf_joint_damping = true;
};

/// Loads and checks a model; dispatches on the extension (.json, .urdf).
/// Throws ModelError naming the file, the place and the fix.
Model load_model(const std::string& path, const LoadOptions& options = {});

}  // namespace kanegen::model
