// SPDX-License-Identifier: GPL-2.0-or-later
// Exact partial derivatives in the expression graph, by the forward-mode
// chain rule: the derivative of a node is built from the derivatives of its
// operands, once per node and variable (memoized), so the intermediates the
// Program named (and the graph shares) are differentiated once and reused
// by every expression that contains them, never expanded. Derivative nodes
// are made by the graph's own canonical constructors, so they share
// subexpressions with the kernels' other nodes and print deterministically;
// a node that does not depend on the variable has the derivative 0, which
// folds away (no code for structural zeros).
#pragma once

#include <vector>

#include "codegen/expression_graph.hpp"

namespace kanegen::codegen {

class GraphDerivative {
 public:
  /// Derivatives with respect to the input node `variable` (e.g. the node of q[2]).
  GraphDerivative(ExpressionGraph& graph, int variable) : graph_(graph), variable_(variable) {}

  /// The node of d(node)/d(variable).
  int of(int node);

 private:
  int derive(int node);
  int product_rule(int node);

  ExpressionGraph& graph_;
  int variable_;
  std::vector<int> memo_;  ///< per node: its derivative, or -1 not yet made
};

/// Whether a node is the number 0.
bool is_zero(const ExpressionGraph& graph, int node);

}  // namespace kanegen::codegen
