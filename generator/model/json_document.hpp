// SPDX-License-Identifier: GPL-2.0-or-later
// Reading a model file as JSON: syntax errors with line and column, and
// duplicate keys (which nlohmann::json would silently collapse) as errors.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace kanegen::model {

/// Reads a whole file; throws ModelError if it cannot be read.
std::string read_text_file(const std::string& path);

/// Parses text read from file; throws ModelError on malformed JSON
/// ("line L, column C") or a key given twice in one object (JSON pointer).
nlohmann::json parse_json_document(const std::string& text, const std::string& file);

/// The JSON pointer token for a key ('~' -> "~0", '/' -> "~1").
std::string pointer_token(const std::string& key);

}  // namespace kanegen::model
