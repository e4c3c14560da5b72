// SPDX-License-Identifier: GPL-2.0-or-later
// The names of a flexible body's elastic coordinates, from the model data
// alone, so that the loader can check the names a model file gives initial
// values for. The finite-element layer names its reduced coordinates by the
// same rule (fem/reduction.hpp; tests/fem checks that the two agree).
#pragma once

#include <string>
#include <vector>

#include "model/model.hpp"

namespace kanegen::model {

/// In coordinate order, without the body prefix: nodal "n<node>.<kind>" for
/// every dof the support leaves free (kinds u, v, theta_z planar; u, v, w,
/// theta_x, theta_y, theta_z spatial), or "mode1", ... for modes and
/// assumed modes. The beam must have passed check_model's beam checks.
std::vector<std::string> elastic_coordinate_names(const ElasticPart& beam);

}  // namespace kanegen::model
