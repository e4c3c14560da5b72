// SPDX-License-Identifier: GPL-2.0-or-later
// URDF robots (revolute, continuous, prismatic and fixed joints) to a Model.
#pragma once

#include <string>

#include "model/load.hpp"
#include "model/model.hpp"

namespace kanegen::model {

/// Reads a .urdf with urdfdom; the root link becomes the ground and the
/// moving joints give the coordinates in the order the file lists them.
/// Throws ModelError naming the URDF element (and its line).
Model load_urdf_model(const std::string& path, const LoadOptions& options);

}  // namespace kanegen::model
