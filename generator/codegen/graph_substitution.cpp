// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/graph_substitution.hpp"

namespace kanegen::codegen {

int GraphSubstitution::of(int node) {
  if (static_cast<std::size_t>(node) >= memo_.size()) memo_.resize(graph_.size(), -1);
  if (memo_[node] >= 0) return memo_[node];
  const int image = rebuild(node);
  // rebuild() may have grown the graph, but not moved this node's slot.
  if (static_cast<std::size_t>(node) >= memo_.size()) memo_.resize(graph_.size(), -1);
  memo_[node] = image;
  return image;
}

int GraphSubstitution::rebuild(int node) {
  const Node n = graph_.node(node);  // a copy: the graph grows below
  if (n.op == Op::number) return node;
  if (n.op == Op::input) {
    const auto found = replacements_.find(node);
    return found == replacements_.end() ? node : found->second;
  }
  std::vector<int> args;
  bool changed = false;
  for (int a : n.args) {
    args.push_back(of(a));
    changed = changed || args.back() != a;
  }
  if (!changed) return node;
  if (n.op == Op::add) return graph_.sum(std::move(args));
  if (n.op == Op::mul) return graph_.product(std::move(args));
  return graph_.apply(n.op, args[0], n.value);
}

}  // namespace kanegen::codegen
