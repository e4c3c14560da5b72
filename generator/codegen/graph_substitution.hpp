// SPDX-License-Identifier: GPL-2.0-or-later
// Inputs of the expression graph replaced by other nodes (u by 0, udot by a
// kernel argument a): a node is rebuilt from its rebuilt operands by the
// graph's canonical constructors, once per node (memoized), so the result
// shares every subexpression it still has with the rest of the graph and
// what a replacement by 0 removes folds away. The graph's intermediates are
// inlined nodes already, so a replacement reaches into them, as a GiNaC
// subs() of a Program's top-level expression does not.
#pragma once

#include <map>
#include <vector>

#include "codegen/expression_graph.hpp"

namespace kanegen::codegen {

class GraphSubstitution {
 public:
  /// `replacements`: input node -> the node that takes its place.
  GraphSubstitution(ExpressionGraph& graph, std::map<int, int> replacements)
      : graph_(graph), replacements_(std::move(replacements)) {}

  /// The node of `node` with the replacements made.
  int of(int node);

 private:
  int rebuild(int node);

  ExpressionGraph& graph_;
  std::map<int, int> replacements_;
  std::vector<int> memo_;  ///< per node: its image, or -1 not yet made
};

}  // namespace kanegen::codegen
