// SPDX-License-Identifier: GPL-2.0-or-later
// Semantic checks shared by the JSON and URDF loaders: names, numbers,
// expressions, mass properties, axes and the joint tree. Runs on the filled
// Model so both formats give the same errors at their own places.
#pragma once

#include <string>

#include "model/model.hpp"

namespace kanegen::model {

/// Checks the model and normalises joint axes to unit length. Errors name
/// model.source_file and the `where` of the offending item (plus "/field");
/// root_place is the place for whole-model problems ("/" or "<robot>").
/// Throws ModelError.
void check_model(Model& model, const std::string& root_place);

}  // namespace kanegen::model
