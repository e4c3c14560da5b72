// SPDX-License-Identifier: GPL-2.0-or-later
// Text from a model (names, file names) in generated C++. Model files, URDFs
// and meshes are untrusted: every text they carry reaches the emitted code
// only through these functions (docs/errors.md#security).
#pragma once

#include <string>

namespace kanegen::codegen {

/// `text` as a C++ string literal, quotes included, that the compiler reads
/// back as exactly these bytes: printable ASCII stays as it is, except that
/// backslash and double quote are escaped, '?' after '?' is written \? (no
/// trigraph), '/' after '*' is written \057 (no comment end); every other byte
/// (control characters, NUL, UTF-8) becomes a three-digit octal escape, which
/// never runs into the next character.
std::string cpp_string_literal(const std::string& text);

/// `text` for a line comment: as it is when it holds only letters, digits and
/// `_ - . + ,` and spaces (the common case, so comments read naturally), else
/// as cpp_string_literal. Either way no newline, no backslash at the line's
/// end, no `*/` and no trigraph reaches the comment.
std::string cpp_comment_text(const std::string& text);

/// `name` as a C++ identifier (a namespace, a Params field). The loaders
/// accept only identifiers there; this throws std::logic_error on anything
/// else, so that a loader's miss can never become code.
const std::string& cpp_identifier(const std::string& name);

/// Throws std::logic_error unless `code` is printable ASCII, spaces and
/// newlines only: the last check on every emitted file, so that no raw
/// control character or byte of a model's text ends up in it.
void check_emitted_text(const std::string& file_name, const std::string& code);

}  // namespace kanegen::codegen
