// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/scalar_type.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "codegen/cpp_printer.hpp"

namespace kanegen::codegen {

std::string ScalarType::literal(double v) const {
  if (is_double()) return format_double(v);
  // The shortest decimal that reads back as the same float: the float is
  // what the kernel computes with, so more digits would only be noise.
  const float f = static_cast<float>(v);
  char buffer[40];
  for (int precision = 1; precision <= 9; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, static_cast<double>(f));
    if (std::strtof(buffer, nullptr) == f) break;
  }
  std::string s = buffer;
  if (s.find_first_of(".einf") == std::string::npos) s += ".0";
  return s + "f";
}

std::string ScalarType::function(const std::string& double_name) const {
  return is_double() ? double_name : double_name + "f";
}

std::string ScalarType::in_type(const std::string& type) const {
  if (is_double()) return type;
  const std::string word = "double";
  const auto identifier = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  std::string out;
  std::size_t from = 0;
  for (std::size_t at = type.find(word); at != std::string::npos; at = type.find(word, at + 1)) {
    const std::size_t end = at + word.size();
    if ((at > 0 && identifier(type[at - 1])) || (end < type.size() && identifier(type[end]))) continue;
    out += type.substr(from, at - from) + name();
    from = end;
  }
  return out + type.substr(from);
}

}  // namespace kanegen::codegen
