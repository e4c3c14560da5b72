// SPDX-License-Identifier: GPL-2.0-or-later
// Semantic checks shared by the JSON and URDF loaders: names, numbers,
// expressions, mass properties, axes and the joint tree. Runs on the filled
// Model so both formats give the same errors at their own places.
#pragma once

#include <string>

#include "model/expression.hpp"
#include "model/model.hpp"

namespace kanegen::model {

/// Checks the model and normalises joint axes to unit length. Errors name
/// model.source_file and the `where` of the offending item (plus "/field");
/// root_place is the place for whole-model problems ("/" or "<robot>").
/// Throws ModelError.
void check_model(Model& model, const std::string& root_place);

/// The physical conditions that depend on the parameters (positive masses,
/// valid inertias, non-negative stiffness, damping and rest lengths),
/// checked at `values` (all parameters), so that `--set m1=-1` is refused
/// before anything is generated or run. `origin` ends the description of a
/// value ("from --set m1=-1"). Throws ModelError naming the file, the place,
/// the body and the parameters of the offending expression.
void check_parameter_values(const Model& model, const ParameterValues& values, const std::string& origin);

}  // namespace kanegen::model
