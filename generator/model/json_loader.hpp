// SPDX-License-Identifier: GPL-2.0-or-later
// The kanegen JSON model format (docs/model-format.md) to a Model.
#pragma once

#include <string>

#include "model/model.hpp"

namespace kanegen::model {

/// Reads, validates (syntax, schema, format rules) and checks a .json model.
/// Throws ModelError.
Model load_json_model(const std::string& path);

}  // namespace kanegen::model
