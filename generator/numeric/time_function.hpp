// SPDX-License-Identifier: GPL-2.0-or-later
// A prescribed motion q(t) of the model language ("(Ws/Ts)*(t^2/2 + ...)")
// parsed once, with the parameters' values folded in, and evaluated over any
// scalar type: with Dual<Dual<double>> seeded along t it gives q, q' and q''
// exactly (the prescribed acceleration). Written for the numeric path, apart
// from model/expression_eval (which evaluates doubles only) and from GiNaC.
//
// Grammar (as model/expression_check, with GiNaC's reading):
//   expression := [+|-] term (('+'|'-') term)*   (a leading sign applies to the first term)
//   term       := factor (('*'|'/') factor)*
//   factor     := primary ['^' primary]          ('^' binds tighter than a sign)
//   primary    := number | name | function '(' expression ')' | '(' expression ')'
#pragma once

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/expression_eval.hpp"
#include "numeric/dual.hpp"

namespace kanegen::numeric {

class TimeFunction {
 public:
  TimeFunction() = default;
  /// Throws std::invalid_argument (naming the expression) on a syntax error
  /// or an unknown name. `variable` is the argument (the time, or x along a
  /// beam for an assumed mode); other names are parameters.
  TimeFunction(const std::string& text, const model::ParameterValues& parameters, const std::string& variable = "t")
      : text_(text), variable_(variable), parameters_(&parameters) {
    root_ = expression();
    skip_space();
    if (at_ < text_.size()) fail("unexpected '" + std::string(1, text_[at_]) + "'");
    parameters_ = nullptr;
  }

  template <class S>
  S operator()(const S& t) const {
    return evaluate(root_, t);
  }

 private:
  enum class Op { number, time, negate, add, subtract, multiply, divide, power, sin, cos, tan, sqrt, exp, log };
  struct Node {
    Op op = Op::number;
    double value = 0;
    int a = -1, b = -1;
    bool varies = false;  ///< depends on t
  };

  template <class S>
  S evaluate(int i, const S& t) const {
    using std::cos;
    using std::exp;
    using std::log;
    using std::pow;
    using std::sin;
    using std::sqrt;
    using std::tan;
    const Node& n = nodes_[i];
    if (!n.varies) return S(n.value);
    switch (n.op) {
      case Op::number:
        return S(n.value);
      case Op::time:
        return t;
      case Op::negate:
        return -evaluate(n.a, t);
      case Op::add:
        return evaluate(n.a, t) + evaluate(n.b, t);
      case Op::subtract:
        return evaluate(n.a, t) - evaluate(n.b, t);
      case Op::multiply:
        return evaluate(n.a, t) * evaluate(n.b, t);
      case Op::divide:
        return evaluate(n.a, t) / evaluate(n.b, t);
      case Op::power:
        if (!nodes_[n.b].varies) return pow(evaluate(n.a, t), nodes_[n.b].value);
        return pow(evaluate(n.a, t), evaluate(n.b, t));
      case Op::sin:
        return sin(evaluate(n.a, t));
      case Op::cos:
        return cos(evaluate(n.a, t));
      case Op::tan:
        return tan(evaluate(n.a, t));
      case Op::sqrt:
        return sqrt(evaluate(n.a, t));
      case Op::exp:
        return exp(evaluate(n.a, t));
      case Op::log:
        return log(evaluate(n.a, t));
    }
    return S(0.0);
  }

  /// A node; a constant subtree is folded to its value at once.
  int add(Op op, int a = -1, int b = -1, double value = 0) {
    Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    n.value = value;
    n.varies = op == Op::time || (a >= 0 && nodes_[a].varies) || (b >= 0 && nodes_[b].varies);
    if (!n.varies && op != Op::number) n.value = fold(n);
    nodes_.push_back(n);
    return static_cast<int>(nodes_.size()) - 1;
  }

  double fold(const Node& n) const {
    const double x = n.a >= 0 ? nodes_[n.a].value : 0, y = n.b >= 0 ? nodes_[n.b].value : 0;
    switch (n.op) {
      case Op::negate:
        return -x;
      case Op::add:
        return x + y;
      case Op::subtract:
        return x - y;
      case Op::multiply:
        return x * y;
      case Op::divide:
        return x / y;
      case Op::power:
        return std::pow(x, y);
      case Op::sin:
        return std::sin(x);
      case Op::cos:
        return std::cos(x);
      case Op::tan:
        return std::tan(x);
      case Op::sqrt:
        return std::sqrt(x);
      case Op::exp:
        return std::exp(x);
      case Op::log:
        return std::log(x);
      default:
        return n.value;
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("cannot read " + std::string(variable_ == "t" ? "prescribed motion" : "expression") +
                                " '" + text_ + "' at column " + std::to_string(at_) + ": " + what);
  }
  void skip_space() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  bool accept(char c) {
    skip_space();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }

  int expression() {
    bool negative = false;
    if (accept('-')) {
      negative = true;
    } else {
      accept('+');
    }
    int value = term();
    if (negative) value = add(Op::negate, value);
    for (;;) {
      if (accept('+')) {
        value = add(Op::add, value, term());
      } else if (accept('-')) {
        value = add(Op::subtract, value, term());
      } else {
        return value;
      }
    }
  }
  int term() {
    int value = factor();
    for (;;) {
      if (accept('*')) {
        value = add(Op::multiply, value, factor());
      } else if (accept('/')) {
        value = add(Op::divide, value, factor());
      } else {
        return value;
      }
    }
  }
  int factor() {
    const int base = primary();
    if (!accept('^')) return base;
    return add(Op::power, base, primary());
  }
  int primary() {
    skip_space();
    if (at_ >= text_.size()) fail("an operand is missing");
    const unsigned char c = static_cast<unsigned char>(text_[at_]);
    if (accept('(')) {
      const int value = expression();
      if (!accept(')')) fail("')' expected");
      return value;
    }
    if (std::isdigit(c) || c == '.') {
      const char* begin = text_.c_str() + at_;
      char* end = nullptr;
      const double value = std::strtod(begin, &end);
      if (end == begin) fail("malformed number");
      at_ += static_cast<std::size_t>(end - begin);
      return add(Op::number, -1, -1, value);
    }
    if (!std::isalpha(c)) fail("an operand is expected");
    const std::size_t start = at_;
    while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_'))
      ++at_;
    const std::string word = text_.substr(start, at_ - start);
    skip_space();
    if (at_ < text_.size() && text_[at_] == '(') {
      ++at_;
      const int x = expression();
      if (!accept(')')) fail("')' expected");
      const Op op = word == "sin"    ? Op::sin
                    : word == "cos"  ? Op::cos
                    : word == "tan"  ? Op::tan
                    : word == "sqrt" ? Op::sqrt
                    : word == "exp"  ? Op::exp
                    : word == "log"  ? Op::log
                                     : Op::number;
      if (op == Op::number) fail("unknown function '" + word + "'");
      return add(op, x);
    }
    if (word == variable_) return add(Op::time);
    if (word == "pi") return add(Op::number, -1, -1, 3.14159265358979323846);
    const auto found = parameters_->find(word);
    if (found == parameters_->end()) fail("unknown name '" + word + "'");
    return add(Op::number, -1, -1, found->second);
  }

  std::string text_;
  std::string variable_;
  const model::ParameterValues* parameters_ = nullptr;  ///< while parsing only
  std::size_t at_ = 0;
  std::vector<Node> nodes_;
  int root_ = -1;
};

}  // namespace kanegen::numeric
