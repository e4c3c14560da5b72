// SPDX-License-Identifier: GPL-2.0-or-later
// Naming rules shared by the loaders: which names are valid identifiers,
// which are taken, and the "did you mean" suggestion for misspellings.
#pragma once

#include <string>
#include <vector>

namespace kanegen::model {

/// A name usable both in C++ and in GiNaC's expression parser:
/// [A-Za-z][A-Za-z0-9_]* (GiNaC's lexer rejects a leading '_').
bool is_identifier(const std::string& name);

/// Why a name (a URDF link's or joint's) cannot be used: "" if it is valid
/// UTF-8 without control characters (newline, tab, NUL, DEL, ...), else what
/// is wrong and at which byte. Such names become CSV columns, JSON keys and
/// string literals in generated code (docs/errors.md#security).
std::string name_text_problem(const std::string& name);

/// C++ keywords and alternative tokens (C++20 included, so generated code
/// stays valid with newer compilers).
bool is_cpp_keyword(const std::string& name);

/// Whether `name` is a macro of the headers generated code includes (errno,
/// EOF, M_PI, linux, ...; read off the compiler at configure time): as a C++
/// identifier (a model's or a parameter's name) the preprocessor would replace it.
bool is_library_macro(const std::string& name);

/// Names a parameter cannot take: the generated code's own names (t, q, u,
/// tau, p), the constant pi, the expression functions and GiNaC's literals.
bool is_reserved_parameter_name(const std::string& name);

/// Turns any text into an identifier (for URDF robot names): other characters
/// become '_', a leading digit or '_' gets a prefix, a keyword or a library
/// macro a suffix.
std::string sanitize_identifier(const std::string& text);

/// Levenshtein distance, for suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The candidate closest to `name` if it is close enough to be a likely
/// misspelling; empty otherwise.
std::string nearest(const std::string& name, const std::vector<std::string>& candidates);

/// "a, b, c" for messages.
std::string join(const std::vector<std::string>& items, const std::string& separator = ", ");

}  // namespace kanegen::model
