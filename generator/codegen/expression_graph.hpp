// SPDX-License-Identifier: GPL-2.0-or-later
// The expression graph: GiNaC expressions (with the Program's intermediates
// inlined) become one hash-consed DAG whose nodes are canonical, so equal
// subexpressions anywhere in the model are one node (common subexpression
// elimination) and the order of operands never depends on GiNaC's
// run-to-run term order.
#pragma once

#include <ginac/ginac.h>

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "symbolic/ex_hash.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::codegen {

enum class Op { number, input, add, mul, power, sin, cos, tan, exp, log, sqrt, abs };

struct Node {
  Op op = Op::number;
  double value = 0.0;     ///< number: its value; power: the exponent
  std::string name;       ///< input: C++ text ("q[0]", "p.m1")
  std::vector<int> args;  ///< operands, in canonical order
  std::uint64_t key = 0;  ///< structural hash, independent of GiNaC's order
};

class ExpressionGraph {
 public:
  ExpressionGraph(const symbolic::Variables& vars, const symbolic::Program& program)
      : vars_(vars), program_(program) {}

  /// Adds an expression; returns its node.
  int add(const GiNaC::ex& e);
  const Node& node(int id) const { return nodes_[id]; }
  std::size_t size() const { return nodes_.size(); }

  // Building nodes directly, in the same canonical form as add() makes them
  // (for derivatives and for kernels that combine equations with arguments).
  /// A number.
  int constant(double v) { return number(v); }
  /// An input that no symbol stands for, e.g. the kernel argument "a[3]".
  int input(const std::string& cpp_name);
  /// The sum and the product of nodes.
  int sum(std::vector<int> terms) { return make_add(std::move(terms)); }
  int product(std::vector<int> factors) { return make_mul(std::move(factors)); }
  /// A function of one node (sqrt, sin, ... ; power with exponent `value`):
  /// an exponent of 0 or 1 and constant arguments fold.
  int apply(Op op, int arg, double value = 0.0);

 private:
  /// A node as coefficient * base; base -1 stands for the number 1.
  struct Term {
    double coefficient;
    int base;
  };
  Term split_coefficient(int id);
  int make_mul(std::vector<int> factors);
  int make_add(std::vector<int> terms);
  int intern(Node node);
  bool same(const Node& a, const Node& b) const;
  int number(double v);
  int convert(const GiNaC::ex& e);
  double fold(const Node& n) const;
  int folded(int id);

  const symbolic::Variables& vars_;
  const symbolic::Program& program_;
  std::vector<Node> nodes_;
  // Hash-consing on the structural key: the newest node with a key, and for
  // each node the previous one with its key (equal keys are told apart by
  // same()); a list threaded through a vector, not a vector per key, which
  // cost an allocation per node. The GiNaC expressions already converted are
  // keyed on GiNaC's hash. Both O(1) where ordered maps on deep compares grew
  // with the model. Neither is iterated, so their order never reaches the output.
  std::unordered_map<std::uint64_t, int> first_with_key_;
  std::vector<int> next_with_key_;
  std::unordered_map<GiNaC::ex, int, symbolic::StoredExHash, GiNaC::ex_is_equal> converted_;
};

}  // namespace kanegen::codegen
