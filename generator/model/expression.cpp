// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/expression.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "model/names.hpp"

// Grammar (recursive descent):
//   expression := [+|-] term (('+'|'-') term)*   (a leading sign applies to the first term)
//   term       := factor (('*'|'/') factor)*
//   factor     := primary ['^' primary]          ('^' binds tighter than a sign: -a^2 = -(a^2))
//   primary    := number | name | function '(' expression ')' | '(' expression ')'
// Two GiNaC parser quirks shape it: a sign right after an operator swallows
// the rest of the expression ("a*-b+c" reads as a*(-b+c)), and "a^b^c" is a
// parse error. Both are rejected here with a hint to add parentheses.

namespace kanegen::model {
namespace {

using Op = ExpressionTree::Op;
using Node = ExpressionTree::Node;

const char* const kAllowed =
    "use numbers, parameter names, + - * / ^, parentheses, sin cos tan sqrt exp log and pi";

struct Token {
  enum Kind { number, name, op, end } kind = end;
  std::string text;
  std::size_t pos = 0;
};

struct Failure {
  ExpressionIssue issue;
};

[[noreturn]] void fail(std::size_t pos, std::string problem, std::string fix) {
  throw Failure{ExpressionIssue{pos, std::move(problem), std::move(fix)}};
}

bool is_function(const std::string& s) {
  return std::any_of(std::begin(kExpressionFunctions), std::end(kExpressionFunctions),
                     [&](const char* f) { return s == f; });
}
bool is_constant(const std::string& s) {
  return std::any_of(std::begin(kExpressionConstants), std::end(kExpressionConstants),
                     [&](const char* c) { return s == c; });
}

Op function_op(const std::string& name) {
  if (name == "sin") return Op::sin;
  if (name == "cos") return Op::cos;
  if (name == "tan") return Op::tan;
  if (name == "sqrt") return Op::sqrt;
  if (name == "exp") return Op::exp;
  return Op::log;
}

/// The value of `n` from the values of its operands.
double fold(const std::vector<Node>& nodes, const Node& n) {
  const double x = n.a >= 0 ? nodes[static_cast<std::size_t>(n.a)].value : 0;
  const double y = n.b >= 0 ? nodes[static_cast<std::size_t>(n.b)].value : 0;
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
    case Op::number:
    case Op::name:
      break;
  }
  return n.value;
}

/// Sets `varies` from the operands and, for a node that does not vary, its value.
void settle(const std::vector<Node>& nodes, Node& n) {
  const auto varies = [&](int i) { return i >= 0 && nodes[static_cast<std::size_t>(i)].varies; };
  if (n.op != Op::name) n.varies = varies(n.a) || varies(n.b);
  if (!n.varies && n.op != Op::number) n.value = fold(nodes, n);
}

/// A number must be a double other than infinity, and not a nonzero value
/// that would become 0. GiNaC reads numbers exactly (it would not finish
/// 1e-5555555555555555555), while the generated code holds doubles.
void check_range(const std::string& number, std::size_t pos) {
  const char* const range =
      "doubles reach from about 1e-308 to 1e308 (2.2e-308 to 1.8e308, subnormals down to 4.9e-324): "
      "write the value within that range, or use other units";
  const auto e = number.find_first_of("eE");
  if (e != std::string::npos) {
    std::string exponent = number.substr(e + 1);
    if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size()));
    if (exponent.size() > 3 || (!exponent.empty() && std::stoi(exponent) > 400))
      fail(pos, "exponent of number '" + number + "' out of range in expression", range);
  }
  const double value = std::strtod(number.c_str(), nullptr);
  if (!std::isfinite(value))
    fail(pos, "number '" + number + "' is too large for a double in expression", range);
  if (value == 0 && number.substr(0, e).find_first_of("123456789") != std::string::npos)
    fail(pos, "number '" + number + "' is too small for a double (it would be 0) in expression", range);
}

/// The end of the number starting at `i`: digits [. digits] | . digits, then
/// [eE][+-]digits, what GiNaC's lexer reads as one number.
std::size_t number_end(const std::string& text, std::size_t i) {
  const auto digit = [&](std::size_t k) {
    return k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]));
  };
  std::size_t j = i;
  while (digit(j)) ++j;
  if (j < text.size() && text[j] == '.') ++j;
  while (digit(j)) ++j;
  if (j < text.size() && (text[j] == 'e' || text[j] == 'E')) {
    std::size_t k = j + 1;
    if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
    if (!digit(k))
      fail(i, "malformed number '" + text.substr(i, k - i) + "' in expression",
           "write numbers like 2, 0.5 or 1e-3");
    while (digit(k)) ++k;
    j = k;
  }
  if (j < text.size() &&
      (text[j] == '.' || text[j] == '_' || std::isalpha(static_cast<unsigned char>(text[j]))))
    fail(j, "malformed number '" + text.substr(i, j - i + 1) + "' in expression",
         "write numbers like 2, 0.5 or 1e-3, and '*' for a product (2*m)");
  return j;
}

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const bool point_digit =
        c == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1]));
    if (std::isspace(c)) {
      ++i;
    } else if (std::isalpha(c)) {
      std::size_t j = i;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      tokens.push_back({Token::name, text.substr(i, j - i), i});
      i = j;
    } else if (std::isdigit(c) || point_digit) {
      const std::size_t j = number_end(text, i);
      check_range(text.substr(i, j - i), i);
      tokens.push_back({Token::number, text.substr(i, j - i), i});
      i = j;
    } else if (std::string("+-*/^(),").find(static_cast<char>(c)) != std::string::npos) {
      if (c == '*' && i + 1 < text.size() && text[i + 1] == '*')
        fail(i, "'**' in expression", "write powers with '^' (l^2)");
      tokens.push_back({Token::op, std::string(1, static_cast<char>(c)), i});
      ++i;
    } else {
      const std::string shown = c < 0x20 || c >= 0x7f ? "a non-ASCII or control character"
                                                      : "'" + std::string(1, static_cast<char>(c)) + "'";
      fail(i, "unexpected " + shown + " in expression", kAllowed);
    }
  }
  tokens.push_back({Token::end, "", text.size()});
  return tokens;
}

/// Builds the tree while checking; every method returns the index of the node it added.
class Parser {
 public:
  Parser(std::vector<Token> tokens, const std::vector<std::string>& names)
      : tokens_(std::move(tokens)), names_(names) {}

  ExpressionTree parse() {
    expression();
    const Token& t = peek();
    if (t.kind == Token::end) return std::move(tree_);
    if (t.text == ")") fail(t.pos, "unmatched ')' in expression", "remove it or add the matching '('");
    fail(t.pos, "unexpected '" + t.text + "' after a complete operand in expression",
         "insert an operator, e.g. '*' for a product (2*m)");
  }

 private:
  const Token& peek() const { return tokens_[next_]; }
  const Token& take() { return tokens_[next_++]; }
  bool is_op(const char* op) const { return peek().kind == Token::op && peek().text == op; }

  int add(Op op, int a = -1, int b = -1) {
    Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    return add(std::move(n));
  }
  int add(Node n) {
    settle(tree_.nodes, n);
    tree_.nodes.push_back(std::move(n));
    return static_cast<int>(tree_.nodes.size()) - 1;
  }

  int expression() {
    bool negative = false;
    if (is_op("+") || is_op("-")) negative = take().text == "-";
    int value = term();
    if (negative) value = add(Op::negate, value);
    while (is_op("+") || is_op("-")) {
      const Op op = take().text == "+" ? Op::add : Op::subtract;
      value = add(op, value, term());
    }
    return value;
  }

  int term() {
    int value = factor();
    while (is_op("*") || is_op("/")) {
      const Op op = take().text == "*" ? Op::multiply : Op::divide;
      value = add(op, value, factor());
    }
    return value;
  }

  int factor() {
    const int base = primary();
    if (!is_op("^")) return base;
    take();
    const std::size_t first = next_;
    const int exponent = primary();
    check_exponent(first, next_, exponent);
    if (is_op("^"))
      fail(peek().pos, "chained '^' in expression",
           "add parentheses to say which power comes first: a^(b^c)");
    return add(Op::power, base, exponent);
  }

  int primary() {
    const Token& t = take();
    switch (t.kind) {
      case Token::number: {
        Node n;
        n.value = std::strtod(t.text.c_str(), nullptr);
        return add(std::move(n));
      }
      case Token::name:
        return name(t);
      case Token::end:
        fail(t.pos, "expression ends where an operand is expected",
             "complete it or remove the trailing operator");
      case Token::op:
        break;
    }
    if (t.text == "(") return parenthesised(t);
    if (t.text == "+" || t.text == "-")
      fail(t.pos, "sign right after an operator in expression",
           "put the signed operand in parentheses, e.g. a*(-b) or x^(-2): GiNaC would read the rest of the "
           "expression into it");
    fail(t.pos, "'" + t.text + "' where an operand is expected in expression",
         "put a number, a parameter or a parenthesised expression there");
  }

  /// The expression after `open`, a '(' already taken, and its ')'.
  int parenthesised(const Token& open) {
    const int value = expression();
    if (is_op(")")) {
      take();
      return value;
    }
    if (peek().kind == Token::end) fail(open.pos, "unclosed '(' in expression", "add the matching ')'");
    const Token& t = peek();
    if (t.text == ",")
      fail(t.pos, "',' in expression", "functions take one argument, and numbers use '.' as decimal point");
    fail(t.pos, "unexpected '" + t.text + "' in expression",
         "insert an operator, e.g. '*' for a product (2*m)");
  }

  /// GiNaC raises exact numbers to exact powers: 5555^55555555 would not
  /// finish. A constant exponent (tokens [first, end) without names, node
  /// `exponent`, folded) must stay within what a double power can use.
  void check_exponent(std::size_t first, std::size_t end, int exponent) const {
    std::string text;
    for (std::size_t k = first; k < end; ++k) {
      if (tokens_[k].kind == Token::name) return;
      text += tokens_[k].text;
    }
    const double value = tree_.nodes[static_cast<std::size_t>(exponent)].value;
    if (std::isfinite(value) && std::abs(value) <= kMaxExponent) return;
    fail(tokens_[first].pos, "exponent " + text + " out of range in expression",
         "use exponents within +-" + std::to_string(static_cast<int>(kMaxExponent)) +
             " (larger powers of doubles overflow or vanish), or write exp(n*log(b))");
  }
  static constexpr double kMaxExponent = 1100.0;

  int name(const Token& t) {
    const bool call = is_op("(");
    if (is_function(t.text)) {
      if (!call)
        fail(t.pos, "'" + t.text + "' is a function", "write its argument in parentheses: " + t.text + "(x)");
      const Token& open = take();
      return add(function_op(t.text), parenthesised(open));
    }
    const bool known = std::find(names_.begin(), names_.end(), t.text) != names_.end();
    if (known || is_constant(t.text)) {
      if (call)
        fail(peek().pos, "'" + t.text + "' is not a function",
             "insert '*' for a product: " + t.text + "*(...)");
      Node n;
      if (is_constant(t.text)) {
        n.value = 3.14159265358979323846;  // pi, the one constant (before any parameter so named)
      } else {
        n.op = Op::name;
        n.name = t.text;
        n.varies = true;  // until bind_expression gives it a value
      }
      return add(std::move(n));
    }
    std::vector<std::string> candidates = names_;
    candidates.insert(candidates.end(), std::begin(kExpressionConstants), std::end(kExpressionConstants));
    candidates.insert(candidates.end(), std::begin(kExpressionFunctions), std::end(kExpressionFunctions));
    const std::string guess = nearest(t.text, candidates);
    fail(t.pos, "unknown name '" + t.text + "' in expression",
         guess.empty() ? "define it under /parameters or fix the spelling"
                       : "did you mean '" + guess + "'? otherwise define it under /parameters");
  }

  std::vector<Token> tokens_;
  const std::vector<std::string>& names_;
  std::size_t next_ = 0;
  ExpressionTree tree_;
};

}  // namespace

ParsedExpression parse_expression(const std::string& text, const std::vector<std::string>& names) {
  ParsedExpression out;
  try {
    if (std::all_of(text.begin(), text.end(),
                    [](char c) { return std::isspace(static_cast<unsigned char>(c)); }))
      fail(0, "empty expression", "write a number or an expression over the parameters");
    out.tree = Parser(tokenize(text), names).parse();
  } catch (const Failure& f) {
    out.issue = f.issue;
  }
  return out;
}

ExpressionTree bind_expression(ExpressionTree tree, const ParameterValues& values,
                               const std::string& variable) {
  for (Node& n : tree.nodes) {
    if (n.op == Op::name) {
      n.varies = !variable.empty() && n.name == variable;
      if (!n.varies) n.value = values.at(n.name);
    }
    settle(tree.nodes, n);
  }
  return tree;
}

}  // namespace kanegen::model
