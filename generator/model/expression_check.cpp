// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/expression_check.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "model/expression_eval.hpp"
#include "model/names.hpp"

// Grammar (recursive descent):
//   expression := [+|-] term (('+'|'-') term)*
//   term       := factor (('*'|'/') factor)*
//   factor     := primary ['^' primary]
//   primary    := number | name | function '(' expression ')' | '(' expression ')'
// Two GiNaC parser quirks shape it: a sign right after an operator swallows
// the rest of the expression ("a*-b+c" reads as a*(-b+c)), and "a^b^c" is a
// parse error. Both are rejected here with a hint to add parentheses.

namespace kanegen::model {
namespace {

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

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  const auto digit = [&](std::size_t k) {
    return k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]));
  };
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isspace(c)) {
      ++i;
    } else if (std::isalpha(c)) {
      std::size_t j = i;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      tokens.push_back({Token::name, text.substr(i, j - i), i});
      i = j;
    } else if (std::isdigit(c) || (c == '.' && digit(i + 1))) {
      // digits [. digits] | . digits, then [eE][+-]digits: what GiNaC's lexer reads as one number.
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

class Parser {
 public:
  Parser(std::vector<Token> tokens, const std::vector<std::string>& parameters)
      : tokens_(std::move(tokens)), parameters_(parameters) {}

  void parse() {
    expression();
    const Token& t = peek();
    if (t.kind == Token::end) return;
    if (t.text == ")") fail(t.pos, "unmatched ')' in expression", "remove it or add the matching '('");
    fail(t.pos, "unexpected '" + t.text + "' after a complete operand in expression",
         "insert an operator, e.g. '*' for a product (2*m)");
  }

 private:
  const Token& peek() const { return tokens_[next_]; }
  const Token& take() { return tokens_[next_++]; }
  bool is_op(const char* op) const { return peek().kind == Token::op && peek().text == op; }

  void expression() {
    if (is_op("+") || is_op("-")) take();
    term();
    while (is_op("+") || is_op("-")) {
      take();
      term();
    }
  }

  void term() {
    factor();
    while (is_op("*") || is_op("/")) {
      take();
      factor();
    }
  }

  void factor() {
    primary();
    if (!is_op("^")) return;
    take();
    const std::size_t first = next_;
    primary();
    check_exponent(first, next_);
    if (is_op("^"))
      fail(peek().pos, "chained '^' in expression",
           "add parentheses to say which power comes first: a^(b^c)");
  }

  void primary() {
    const Token& t = take();
    switch (t.kind) {
      case Token::number:
        return;
      case Token::name:
        return name(t);
      case Token::end:
        fail(t.pos, "expression ends where an operand is expected",
             "complete it or remove the trailing operator");
      case Token::op:
        break;
    }
    if (t.text == "(") {
      expression();
      if (!is_op(")")) {
        if (peek().kind == Token::end) fail(t.pos, "unclosed '(' in expression", "add the matching ')'");
        parse_rest_error();
      }
      take();
      return;
    }
    if (t.text == "+" || t.text == "-")
      fail(t.pos, "sign right after an operator in expression",
           "put the signed operand in parentheses, e.g. a*(-b) or x^(-2): GiNaC would read the rest of the "
           "expression into it");
    fail(t.pos, "'" + t.text + "' where an operand is expected in expression",
         "put a number, a parameter or a parenthesised expression there");
  }

  /// GiNaC raises exact numbers to exact powers: 5555^55555555 would not
  /// finish. A constant exponent (tokens [first, end) without names) must
  /// stay within what a double power can use.
  void check_exponent(std::size_t first, std::size_t end) const {
    std::string text;
    for (std::size_t k = first; k < end; ++k) {
      if (tokens_[k].kind == Token::name) return;
      text += tokens_[k].text;
    }
    double value = 0.0;
    try {
      value = evaluate_expression(text, {});
    } catch (const std::exception&) {
      return;  // the parse reports what is wrong with it
    }
    if (std::isfinite(value) && std::abs(value) <= kMaxExponent) return;
    fail(tokens_[first].pos, "exponent " + text + " out of range in expression",
         "use exponents within +-" + std::to_string(static_cast<int>(kMaxExponent)) +
             " (larger powers of doubles overflow or vanish), or write exp(n*log(b))");
  }
  static constexpr double kMaxExponent = 1100.0;

  [[noreturn]] void parse_rest_error() {
    const Token& t = peek();
    if (t.text == ",")
      fail(t.pos, "',' in expression", "functions take one argument, and numbers use '.' as decimal point");
    fail(t.pos, "unexpected '" + t.text + "' in expression",
         "insert an operator, e.g. '*' for a product (2*m)");
  }

  void name(const Token& t) {
    const bool call = is_op("(");
    const bool parameter = std::find(parameters_.begin(), parameters_.end(), t.text) != parameters_.end();
    if (is_function(t.text)) {
      if (!call)
        fail(t.pos, "'" + t.text + "' is a function", "write its argument in parentheses: " + t.text + "(x)");
      const Token& open = take();
      expression();
      if (is_op(")")) {
        take();
        return;
      }
      if (peek().kind == Token::end) fail(open.pos, "unclosed '(' in expression", "add the matching ')'");
      parse_rest_error();
    }
    if (parameter || is_constant(t.text)) {
      if (call)
        fail(peek().pos, "'" + t.text + "' is not a function",
             "insert '*' for a product: " + t.text + "*(...)");
      return;
    }
    std::vector<std::string> known = parameters_;
    known.insert(known.end(), std::begin(kExpressionConstants), std::end(kExpressionConstants));
    known.insert(known.end(), std::begin(kExpressionFunctions), std::end(kExpressionFunctions));
    const std::string guess = nearest(t.text, known);
    fail(t.pos, "unknown name '" + t.text + "' in expression",
         guess.empty() ? "define it under /parameters or fix the spelling"
                       : "did you mean '" + guess + "'? otherwise define it under /parameters");
  }

  std::vector<Token> tokens_;
  const std::vector<std::string>& parameters_;
  std::size_t next_ = 0;
};

}  // namespace

std::optional<ExpressionIssue> check_expression(const std::string& text,
                                                const std::vector<std::string>& parameters) {
  try {
    if (std::all_of(text.begin(), text.end(),
                    [](char c) { return std::isspace(static_cast<unsigned char>(c)); }))
      fail(0, "empty expression", "write a number or an expression over the parameters");
    Parser(tokenize(text), parameters).parse();
  } catch (const Failure& f) {
    return f.issue;
  }
  return std::nullopt;
}

std::string describe_with_caret(const std::string& text, const ExpressionIssue& issue) {
  // Tabs, newlines and other control characters would misplace the caret
  // or break the line; show them as spaces.
  std::string shown = text;
  std::replace_if(
      shown.begin(), shown.end(),
      [](char c) { return static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f; },
      ' ');
  return issue.problem + "\n  " + shown + "\n  " + std::string(std::min(issue.column, shown.size()), ' ') +
         "^";
}

}  // namespace kanegen::model
