// SPDX-License-Identifier: GPL-2.0-or-later
// The JSON Schema of the model format (models/schema/kanegen-model.schema.json,
// embedded at build time) and validation against it with valijson.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace kanegen::model {

/// The schema text, as in models/schema/kanegen-model.schema.json.
const char* model_schema_text();

/// Validates a parsed model file. On failure throws ModelError with the first
/// problem in one line: the JSON pointer, what is wrong and how to fix it
/// (nearest known key, allowed values, expected type), not valijson's dump.
void validate_model_schema(const nlohmann::json& document, const std::string& file);

}  // namespace kanegen::model
