// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/names.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "model/expression.hpp"

namespace kanegen::model {

namespace {

// ASCII only, whatever the locale: std::isalpha takes Latin-1 letters in some.
bool ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool ascii_alnum(char c) { return ascii_letter(c) || (c >= '0' && c <= '9'); }

/// The length of the valid UTF-8 sequence at text[i] (1-4), or 0.
std::size_t utf8_sequence(const std::string& text, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = b(i);
  if (lead < 0x80) return 1;
  // The sequence's length, and its smallest code point (a smaller one is overlong).
  const std::size_t length = lead >= 0xf0 ? 4 : lead >= 0xe0 ? 3 : 2;
  const unsigned min = length == 4 ? 0x10000 : length == 3 ? 0x800 : 0x80;
  if (lead < 0xc2 || lead > 0xf4) return 0;  // a continuation byte, or an overlong or too large lead
  if (i + length > text.size()) return 0;
  unsigned code = lead & (0x7f >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((b(i + k) & 0xc0) != 0x80) return 0;
    code = (code << 6) | (b(i + k) & 0x3f);
  }
  // No overlong form, no surrogate, nothing past U+10FFFF.
  if (code < min || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff) return 0;
  return length;
}

}  // namespace

bool is_identifier(const std::string& name) {
  if (name.empty() || !ascii_letter(name[0])) return false;
  return std::all_of(name.begin(), name.end(), [](char c) { return ascii_alnum(c) || c == '_'; });
}

std::string name_text_problem(const std::string& name) {
  for (std::size_t i = 0; i < name.size();) {
    const auto byte = static_cast<unsigned char>(name[i]);
    if (byte < 0x20 || byte == 0x7f) {
      static const char* const hex = "0123456789abcdef";
      return std::string("a control character (byte 0x") + hex[byte >> 4] + hex[byte & 15] + ") at byte " +
             std::to_string(i + 1);
    }
    const std::size_t length = utf8_sequence(name, i);
    if (length == 0) return "a byte that is not UTF-8 at byte " + std::to_string(i + 1);
    i += length;
  }
  return "";
}

extern const char* const library_macros[];  // library_macros.cpp, made by cmake/LibraryMacros.cmake
extern const std::size_t library_macro_count;

bool is_library_macro(const std::string& name) {
  return std::find(library_macros, library_macros + library_macro_count, name) !=
         library_macros + library_macro_count;
}

bool is_cpp_keyword(const std::string& name) {
  static const std::set<std::string> keywords{
      "alignas",     "alignof",   "and",        "and_eq",    "asm",      "auto",         "bitand",
      "bitor",       "bool",      "break",      "case",      "catch",    "char",         "char8_t",
      "char16_t",    "char32_t",  "class",      "compl",     "concept",  "const",        "consteval",
      "constexpr",   "constinit", "const_cast", "continue",  "co_await", "co_return",    "co_yield",
      "decltype",    "default",   "delete",     "do",        "double",   "dynamic_cast", "else",
      "enum",        "explicit",  "export",     "extern",    "false",    "float",        "for",
      "friend",      "goto",      "if",         "inline",    "int",      "long",         "mutable",
      "namespace",   "new",       "noexcept",   "not",       "not_eq",   "nullptr",      "operator",
      "or",          "or_eq",     "private",    "protected", "public",   "register",     "reinterpret_cast",
      "requires",    "return",    "short",      "signed",    "sizeof",   "static",       "static_assert",
      "static_cast", "struct",    "switch",     "template",  "this",     "thread_local", "throw",
      "true",        "try",       "typedef",    "typeid",    "typename", "union",        "unsigned",
      "using",       "virtual",   "void",       "volatile",  "wchar_t",  "while",        "xor",
      "xor_eq"};
  return keywords.count(name) > 0;
}

bool is_reserved_parameter_name(const std::string& name) {
  static const std::set<std::string> reserved{"t", "q", "u", "tau", "p", "I", "Pi", "Euler", "Catalan"};
  if (reserved.count(name) > 0) return true;
  for (const char* c : kExpressionConstants)
    if (name == c) return true;
  for (const char* f : kExpressionFunctions)
    if (name == f) return true;
  return false;
}

std::string sanitize_identifier(const std::string& text) {
  std::string out;
  for (char c : text) out += ascii_alnum(c) ? c : '_';
  if (out.empty() || !ascii_letter(out[0])) out = "model_" + out;
  if (is_cpp_keyword(out) || is_library_macro(out)) out += '_';
  return out;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearest(const std::string& name, const std::vector<std::string>& candidates) {
  // Allow about one typo per three characters: "mas" -> "mass", not "x" -> "q".
  const std::size_t limit = std::max<std::size_t>(1, (name.size() + 1) / 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d >= std::max(name.size(), c.size())) continue;  // nothing in common: "c" is no typo of "a"
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : std::string()) + items[i];
  return out;
}

}  // namespace kanegen::model
