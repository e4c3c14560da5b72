// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/graph_derivative.hpp"

#include <stdexcept>

namespace kanegen::codegen {

bool is_zero(const ExpressionGraph& graph, int node) {
  const Node& n = graph.node(node);
  return n.op == Op::number && n.value == 0.0;
}

int GraphDerivative::of(int node) {
  if (static_cast<std::size_t>(node) >= memo_.size()) memo_.resize(graph_.size(), -1);
  if (memo_[node] >= 0) return memo_[node];
  const int d = derive(node);
  // derive() may have grown the graph, but not moved this node's slot.
  if (static_cast<std::size_t>(node) >= memo_.size()) memo_.resize(graph_.size(), -1);
  memo_[node] = d;
  return d;
}

// d(a b c) = da b c + a db c + a b dc, only over the factors that depend on
// the variable (a product of many factors rarely has more than one or two).
int GraphDerivative::product_rule(int node) {
  const std::vector<int> args = graph_.node(node).args;  // a copy: the graph grows below
  std::vector<int> terms;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const int d = of(args[i]);
    if (is_zero(graph_, d)) continue;
    std::vector<int> factors{d};
    for (std::size_t j = 0; j < args.size(); ++j)
      if (j != i) factors.push_back(args[j]);
    terms.push_back(graph_.product(std::move(factors)));
  }
  return graph_.sum(std::move(terms));
}

int GraphDerivative::derive(int node) {
  const Node n = graph_.node(node);  // a copy: the graph grows below
  if (n.op == Op::number) return graph_.constant(0.0);
  if (n.op == Op::input) return graph_.constant(node == variable_ ? 1.0 : 0.0);
  if (n.op == Op::add) {
    std::vector<int> terms;
    for (int a : n.args) terms.push_back(of(a));
    return graph_.sum(std::move(terms));
  }
  if (n.op == Op::mul) return product_rule(node);
  const int x = n.args[0];
  const int dx = of(x);
  if (is_zero(graph_, dx)) return dx;
  int outer = -1;  // d f(x) / dx
  switch (n.op) {
    case Op::power:
      outer = graph_.product({graph_.constant(n.value), graph_.apply(Op::power, x, n.value - 1.0)});
      break;
    case Op::sqrt:  // 1 / (2 sqrt(x))
      outer = graph_.product({graph_.constant(0.5), graph_.apply(Op::power, node, -1.0)});
      break;
    case Op::sin:
      outer = graph_.apply(Op::cos, x);
      break;
    case Op::cos:
      outer = graph_.product({graph_.constant(-1.0), graph_.apply(Op::sin, x)});
      break;
    case Op::tan:  // 1 + tan(x)^2
      outer = graph_.sum({graph_.constant(1.0), graph_.apply(Op::power, node, 2.0)});
      break;
    case Op::exp:
      outer = node;
      break;
    case Op::log:
      outer = graph_.apply(Op::power, x, -1.0);
      break;
    case Op::abs:  // sign(x) = x / |x| (undefined at 0, as the derivative)
      outer = graph_.product({x, graph_.apply(Op::power, node, -1.0)});
      break;
    default:
      throw std::logic_error("graph derivative: unexpected operation");
  }
  return graph_.product({outer, dx});
}

}  // namespace kanegen::codegen
