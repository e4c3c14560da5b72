// SPDX-License-Identifier: MIT
// Strict number parsing and round-trip formatting shared by the runner's
// command line, its JSON output and the CSV writer.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace kanegen::runtime {

/// Parses a finite decimal number ("1", "-2.5e-3"); the whole text must be
/// the number. Rejects "", "1.2x", " 1", "nan", "inf", hex and overflow.
bool parse_number(std::string_view text, double* value);

/// Parses "v1,v2,..." with parse_number for each entry; "" is the empty list.
bool parse_number_list(std::string_view text, std::vector<double>* values);

/// Parses a decimal integer (optional sign, digits only).
bool parse_integer(std::string_view text, long* value);

/// "%.17g": enough digits that parsing the text gives back the same double.
std::string format_double(double value);

/// A JSON number in "%.17g", or null when the value is NaN or infinite
/// (JSON has no such numbers).
std::string json_number(double value);

/// A JSON string literal with quotes and escapes.
std::string json_string(std::string_view text);

/// names[0], names[1], ... joined with ", ".
std::string join_names(const char* const* names, int n);

}  // namespace kanegen::runtime
