// SPDX-License-Identifier: GPL-2.0-or-later
// Checks on generated C++ shared by the names fuzzer (fuzz/names_fuzzer.cpp)
// and the injection test (tests/security): the generated code of a model is
// compared, after `g++ -E -P`, with that of the same model whose names are
// placeholders. Any token the names brought in (a directive, a comment end,
// a macro's expansion) shows up as a difference; every string literal must
// read back as the placeholder's one with the names put back.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kanegen::fuzz {

/// A name for messages: every byte outside printable ASCII (and '\') as \xNN.
std::string shown(const std::string& text);

/// The bytes of a file ("" if it cannot be read).
std::string read_file(const std::filesystem::path& path);

/// `g++ -std=c++17 -E -P` of a generated .cpp, with its own directory and
/// `runtime_include` on the include path, run without a shell (paths may
/// hold any byte); g++'s output and messages go through files in `out_dir`.
/// Returns the output; throws HarnessFailure with g++'s messages if it fails.
std::string preprocess(const std::filesystem::path& cpp, const std::filesystem::path& runtime_include,
                       const std::filesystem::path& out_dir);

struct Token {
  std::string text;  ///< as written; a string literal with its quotes
  bool literal = false;
};

/// The tokens of preprocessed C++, coarsely but the same way for both runs:
/// whitespace skipped; "..." and '...' (with their escapes) one token each;
/// a run of letters, digits and '_' one token (a number keeps its '.',
/// digit separators and exponent sign); any other character one token.
std::vector<Token> tokenize(const std::string& text);

/// The bytes a string literal token stands for (C escapes: simple, octal,
/// hex); throws HarnessFailure for an unknown escape.
std::string decode_literal(const std::string& token);

/// Placeholder -> the name the loader read in its place.
using NameMap = std::map<std::string, std::string>;

/// `text` with every placeholder replaced by its name (placeholders must not
/// be prefixes of one another).
std::string substitute(const std::string& text, const NameMap& names);

/// The two token streams must agree token for token: string literals by
/// what they read (the placeholder model's with the names put back; not
/// compared if `literals` is false, when the names are not known), other
/// tokens as written after the same substitution, where a name that became
/// an identifier token must be a usable identifier. Throws HarnessFailure
/// naming `file` and the first difference.
void compare_tokens(const std::string& file, const std::vector<Token>& placeholder,
                    const std::vector<Token>& named, const NameMap& names, bool literals = true);

}  // namespace kanegen::fuzz
