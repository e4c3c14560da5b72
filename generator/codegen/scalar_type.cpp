// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/scalar_type.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>

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

std::string ScalarType::in_code(const std::string& double_code) const {
  if (is_double()) return double_code;
  static const std::set<std::string> math = {"sin",   "cos", "tan", "asin", "acos", "atan",
                                             "atan2", "exp", "log", "sqrt", "pow",  "fabs"};
  const auto identifier = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  const std::string& in = double_code;
  const auto refuse = [&](std::size_t at, const char* what) {
    const std::size_t line = static_cast<std::size_t>(std::count(in.begin(), in.begin() + at, '\n')) + 1;
    throw std::logic_error(std::string("ScalarType::in_code: ") + what + " on line " + std::to_string(line) +
                           " of the code to convert is not handled; write it without, or extend in_code");
  };
  std::string out;
  std::size_t at = 0;
  while (at < in.size()) {
    if (in[at] == '"' || in[at] == '\'') refuse(at, "a string or character literal");
    if (in.compare(at, 2, "/*") == 0) refuse(at, "a block comment");
    if (in[at] == '.' && at + 1 < in.size() && std::isdigit(static_cast<unsigned char>(in[at + 1])) &&
        (at == 0 || !identifier(in[at - 1])))
      refuse(at, "a number with a leading dot");
    if (in.compare(at, 5, "std::") == 0 && (at == 0 || !identifier(in[at - 1]))) refuse(at, "a std:: name");
    if (in.compare(at, 2, "0x") == 0 || in.compare(at, 2, "0X") == 0) refuse(at, "a hexadecimal number");
    if (in.compare(at, 2, "M_") == 0 && (at == 0 || !identifier(in[at - 1])))
      refuse(at, "a <math.h> constant");
    if (in.compare(at, 2, "//") == 0) {  // a comment, to the end of its line
      const std::size_t end = std::min(in.find('\n', at), in.size());
      out += in.substr(at, end - at);
      at = end;
    } else if (std::isdigit(static_cast<unsigned char>(in[at]))) {  // a number: digits, '.', exponent
      std::size_t end = at;
      while (end < in.size() &&
             (identifier(in[end]) || in[end] == '.' ||
              ((in[end] == '-' || in[end] == '+') && (in[end - 1] == 'e' || in[end - 1] == 'E'))))
        ++end;
      const std::string number = in.substr(at, end - at);
      const bool floating = number.find_first_of(".eE") != std::string::npos;
      out += floating ? literal(std::strtod(number.c_str(), nullptr)) : number;
      at = end;
    } else if (identifier(in[at])) {  // a word: the type, a <math.h> function, or any other name
      std::size_t end = at;
      while (end < in.size() && identifier(in[end])) ++end;
      const std::string word = in.substr(at, end - at);
      if (word == "double")
        out += name();
      else if (math.count(word) && end < in.size() && in[end] == '(')
        out += function(word);
      else
        out += word;
      at = end;
    } else {
      out += in[at++];
    }
  }
  return out;
}

}  // namespace kanegen::codegen
