// SPDX-License-Identifier: GPL-2.0-or-later
// The model's expression language ("m1*l1^2/12", "(Ws/Ts)*(t^2/2 + ...)"),
// read by one parser for all its users: the load-time check with a caret
// under the culprit (expression_check), values at given parameters
// (expression_eval) and the prescribed motions of the numeric path over dual
// numbers (numeric/time_function). No GiNaC here: the symbolic path reads the
// same text with GiNaC's parser, and the accepted language is a subset of
// what GiNaC reads with the same meaning (the rules that keep it so are in
// expression.cpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace kanegen::model {

/// Functions of one argument usable in expressions (all in GiNaC's parser table).
inline constexpr const char* kExpressionFunctions[] = {"sin", "cos", "tan", "sqrt", "exp", "log"};
/// Named constants; the generator maps "pi" to GiNaC::Pi.
inline constexpr const char* kExpressionConstants[] = {"pi"};

struct ExpressionIssue {
  std::size_t column = 0;  ///< byte offset into the text where the problem starts
  std::string problem;     ///< e.g. "unknown name 'm2' in expression"
  std::string fix;
};

/// Parameter name -> value.
using ParameterValues = std::map<std::string, double>;

/// A parsed expression. Nodes are stored children first, so the root is the
/// last node and one forward pass sees every operand before its user.
struct ExpressionTree {
  enum class Op {
    number,
    name,
    negate,
    add,
    subtract,
    multiply,
    divide,
    power,
    sin,
    cos,
    tan,
    sqrt,
    exp,
    log
  };
  struct Node {
    Op op = Op::number;
    double value = 0;    ///< of a number; of every node with varies == false
    std::string name;    ///< of a parameter (Op::name)
    int a = -1, b = -1;  ///< operands (node indices)
    bool varies =
        false;  ///< value not known: a name, or depends on one (after bind_expression: on the variable)
  };
  std::vector<Node> nodes;
};

struct ParsedExpression {
  ExpressionTree tree;                   ///< empty if there is an issue
  std::optional<ExpressionIssue> issue;  ///< the first problem, if any
};

/// Parses `text`, checking tokens, grammar and that every name is one of
/// `names`, a constant or a function. Subtrees of numbers alone are folded.
ParsedExpression parse_expression(const std::string& text, const std::vector<std::string>& names);

/// The tree with the values of its names put in and every subtree that does
/// not depend on `variable` (empty: none) folded to its double value, so that
/// evaluation repeats only the part that varies. Throws std::out_of_range
/// for a name (other than `variable`) without a value.
ExpressionTree bind_expression(ExpressionTree tree, const ParameterValues& values,
                               const std::string& variable = "");

namespace detail {

template <class S>
S evaluate_node(const ExpressionTree& tree, int i, const S& x) {
  using Op = ExpressionTree::Op;
  using std::cos;
  using std::exp;
  using std::log;
  using std::pow;
  using std::sin;
  using std::sqrt;
  using std::tan;
  const ExpressionTree::Node& n = tree.nodes[static_cast<std::size_t>(i)];
  if (!n.varies) return S(n.value);
  switch (n.op) {
    case Op::number:
      return S(n.value);
    case Op::name:
      return x;
    case Op::negate:
      return -evaluate_node(tree, n.a, x);
    case Op::add:
      return evaluate_node(tree, n.a, x) + evaluate_node(tree, n.b, x);
    case Op::subtract:
      return evaluate_node(tree, n.a, x) - evaluate_node(tree, n.b, x);
    case Op::multiply:
      return evaluate_node(tree, n.a, x) * evaluate_node(tree, n.b, x);
    case Op::divide:
      return evaluate_node(tree, n.a, x) / evaluate_node(tree, n.b, x);
    case Op::power: {
      // A constant exponent stays a double: pow(Dual, double) is the plain power rule.
      const ExpressionTree::Node& exponent = tree.nodes[static_cast<std::size_t>(n.b)];
      if (!exponent.varies) return pow(evaluate_node(tree, n.a, x), exponent.value);
      return pow(evaluate_node(tree, n.a, x), evaluate_node(tree, n.b, x));
    }
    case Op::sin:
      return sin(evaluate_node(tree, n.a, x));
    case Op::cos:
      return cos(evaluate_node(tree, n.a, x));
    case Op::tan:
      return tan(evaluate_node(tree, n.a, x));
    case Op::sqrt:
      return sqrt(evaluate_node(tree, n.a, x));
    case Op::exp:
      return exp(evaluate_node(tree, n.a, x));
    case Op::log:
      return log(evaluate_node(tree, n.a, x));
  }
  return S(0.0);
}

}  // namespace detail

/// The value of a tree from bind_expression with its variable at `x`, over any
/// scalar type S that a double converts to and that has + - * /, pow, sin,
/// cos, tan, sqrt, exp and log: double, or numeric::Dual<...> for derivatives.
template <class S>
S evaluate_tree(const ExpressionTree& bound, const S& x) {
  if (bound.nodes.empty()) return S(0.0);
  return detail::evaluate_node(bound, static_cast<int>(bound.nodes.size()) - 1, x);
}

}  // namespace kanegen::model
