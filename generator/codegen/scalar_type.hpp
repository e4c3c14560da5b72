// SPDX-License-Identifier: GPL-2.0-or-later
// The floating-point type of the emitted code: double (the default, what the
// runtime runs) or float (`kanegen generate --precision float`, for an FPU
// that only has single precision, such as a Cortex-M4F's). It names the
// type, writes its literals and names the <math.h> function of each
// operation, so that the printers never spell `double` themselves.
#pragma once

#include <string>

namespace kanegen::codegen {

enum class Precision { double_precision, single_precision };

class ScalarType {
 public:
  explicit ScalarType(Precision precision = Precision::double_precision) : precision_(precision) {}

  Precision precision() const { return precision_; }
  bool is_double() const { return precision_ == Precision::double_precision; }
  /// "double" or "float".
  const char* name() const { return is_double() ? "double" : "float"; }
  /// The shortest text that reads back as v in this type: "0.5", "0.5f".
  std::string literal(double v) const;
  /// The <math.h> function for a double one: "sin" -> "sin" or "sinf".
  std::string function(const std::string& double_name) const;
  /// `type` (a C++ type as the kernel table writes it, e.g. "const double*")
  /// with each word "double" replaced by this type's name.
  std::string in_type(const std::string& type) const;
  /// C++ code written for double (the saddle-point solve of
  /// templates/solve_saddle.hpp) in this type: the word "double", every
  /// floating literal and every <math.h> call; comments are left as they are.
  /// It reads the subset of C++ the template is written in, and throws
  /// std::logic_error on anything it would get wrong (a string or character
  /// literal, a block comment, a hexadecimal or a leading-dot number, a
  /// std:: qualified call, M_PI), so that a template edit cannot leave a
  /// double behind unnoticed.
  std::string in_code(const std::string& double_code) const;

 private:
  Precision precision_;
};

}  // namespace kanegen::codegen
