// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/cpp_text.hpp"

#include <stdexcept>

#include "model/names.hpp"

namespace kanegen::codegen {

std::string cpp_string_literal(const std::string& text) {
  std::string out = "\"";
  char previous = '\0';
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (c == '?' && previous == '?') {
      out += "\\?";
    } else if (c == '/' && previous == '*') {
      out += "\\057";
    } else if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      const char octal[] = {'\\', static_cast<char>('0' + (byte >> 6)),
                            static_cast<char>('0' + ((byte >> 3) & 7)), static_cast<char>('0' + (byte & 7)),
                            '\0'};
      out += octal;
    }
    previous = c;
  }
  return out + "\"";
}

std::string cpp_comment_text(const std::string& text) {
  if (text.empty()) return cpp_string_literal(text);
  for (const char c : text) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '_' || c == '-' || c == '.' || c == '+' || c == ',' || c == ' ';
    if (!plain) return cpp_string_literal(text);
  }
  return text;
}

const std::string& cpp_identifier(const std::string& name) {
  if (!model::is_identifier(name) || model::is_cpp_keyword(name) || model::is_library_macro(name))
    throw std::logic_error("not a C++ identifier, refused for generated code: " + cpp_string_literal(name));
  return name;
}

void check_emitted_text(const std::string& file_name, const std::string& code) {
  for (std::size_t i = 0; i < code.size(); ++i) {
    const auto byte = static_cast<unsigned char>(code[i]);
    if (byte != '\n' && (byte < 0x20 || byte >= 0x7f))
      throw std::logic_error(file_name + ": byte " + std::to_string(byte) + " at offset " +
                             std::to_string(i) + " of the generated code is not printable ASCII");
  }
}

}  // namespace kanegen::codegen
