// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/expression_eval.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

// Recursive descent over the grammar of expression_check.cpp:
//   expression := [+|-] term (('+'|'-') term)*
//   term       := factor (('*'|'/') factor)*
//   factor     := primary ['^' primary]
//   primary    := number | name | function '(' expression ')' | '(' expression ')'
// evaluating as it parses (expressions are short and evaluated once per
// parameter set, so no syntax tree is kept).

namespace kanegen::model {
namespace {

class Evaluator {
 public:
  Evaluator(const std::string& text, const ParameterValues& parameters)
      : text_(text), parameters_(parameters) {}

  double run() {
    const double value = expression();
    skip_space();
    if (at_ < text_.size()) fail("unexpected '" + std::string(1, text_[at_]) + "'");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("cannot evaluate expression '" + text_ + "' at column " +
                                std::to_string(at_) + ": " + what);
  }

  void skip_space() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }

  /// Consumes `c` if it is the next character.
  bool accept(char c) {
    skip_space();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }

  double expression() {
    double sign = 1.0;
    if (accept('-')) {
      sign = -1.0;
    } else {
      accept('+');
    }
    double value = sign * term();
    for (;;) {
      if (accept('+')) {
        value += term();
      } else if (accept('-')) {
        value -= term();
      } else {
        return value;
      }
    }
  }

  double term() {
    double value = factor();
    for (;;) {
      if (accept('*')) {
        value *= factor();
      } else if (accept('/')) {
        value /= factor();
      } else {
        return value;
      }
    }
  }

  double factor() {
    const double base = primary();
    if (!accept('^')) return base;
    return std::pow(base, primary());
  }

  double primary() {
    skip_space();
    if (at_ >= text_.size()) fail("an operand is missing");
    const unsigned char c = static_cast<unsigned char>(text_[at_]);
    if (accept('(')) {
      const double value = expression();
      if (!accept(')')) fail("')' expected");
      return value;
    }
    if (std::isdigit(c) || c == '.') return number();
    if (std::isalpha(c)) return name();
    fail("an operand is expected");
  }

  double number() {
    const char* begin = text_.c_str() + at_;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin) fail("malformed number");
    at_ += static_cast<std::size_t>(end - begin);
    return value;
  }

  double name() {
    const std::size_t start = at_;
    while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_'))
      ++at_;
    const std::string word = text_.substr(start, at_ - start);
    skip_space();
    if (at_ < text_.size() && text_[at_] == '(') {
      ++at_;
      const double x = expression();
      if (!accept(')')) fail("')' expected");
      return call(word, x);
    }
    if (word == "pi") return 3.14159265358979323846;
    const auto found = parameters_.find(word);
    if (found == parameters_.end()) fail("unknown name '" + word + "'");
    return found->second;
  }

  double call(const std::string& function, double x) const {
    if (function == "sin") return std::sin(x);
    if (function == "cos") return std::cos(x);
    if (function == "tan") return std::tan(x);
    if (function == "sqrt") return std::sqrt(x);
    if (function == "exp") return std::exp(x);
    if (function == "log") return std::log(x);
    fail("unknown function '" + function + "'");
  }

  const std::string& text_;
  const ParameterValues& parameters_;
  std::size_t at_ = 0;
};

}  // namespace

ParameterValues default_parameter_values(const Model& model) {
  ParameterValues values;
  for (const Parameter& p : model.parameters) values[p.name] = p.value;
  return values;
}

double evaluate_expression(const std::string& text, const ParameterValues& parameters) {
  return Evaluator(text, parameters).run();
}

double evaluate(const Scalar& scalar, const ParameterValues& parameters) {
  return scalar.is_literal ? scalar.value : evaluate_expression(scalar.text, parameters);
}

}  // namespace kanegen::model
