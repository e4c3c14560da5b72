// SPDX-License-Identifier: GPL-2.0-or-later
// The bodies of a model's kernels, from its equations: each kernel of the
// kernel table that the model has (those of loops only for closed loops) as
// statements printed from the expression graph.
#pragma once

#include <vector>

#include "codegen/expression_graph.hpp"
#include "codegen/kernel_printer.hpp"
#include "codegen/scalar_type.hpp"
#include "kane/equations.hpp"
#include "model/model.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::codegen {

/// How forward_dynamics solves M u_dot = f on an open rigid tree: the
/// articulated-body recursion (O(n)), M and f by composite inertias then an
/// unrolled LDL^T (O(n^3)), or whichever has fewer operations.
enum class DynamicsMethod { automatic, recursive, composite };

/// What forward_dynamics was made with, and the operations of both ways
/// (recursive_operations is -1 where the recursion does not apply).
struct DynamicsChoice {
  bool recursive = false;
  long composite_operations = 0, recursive_operations = -1;
};

/// In kernel-table order, each kernel's derive function asking `products`
/// for what it needs (so only those products are derived); the Jacobian
/// kernels only with `jacobians`, the quadratic controller kernels only with
/// `controller` (which needs `jacobians`); the bodies in the floating-point
/// type `scalar`; `dynamics`: forward_dynamics's method (recursive needs
/// kane::Recursion::accelerations, else std::logic_error), reported in
/// `choice`; `split_threshold`: kernels of more statements are split into
/// functions (kernel_splitter.hpp; 0: never). `graph` is of the products' program.
std::vector<KernelCode> derive_kernels(kane::DerivationContext& products, ExpressionGraph& graph,
                                       bool jacobians = false, bool controller = false,
                                       const ScalarType& scalar = ScalarType(),
                                       DynamicsMethod dynamics = DynamicsMethod::automatic,
                                       DynamicsChoice* choice = nullptr, int split_threshold = 0);

/// DynamicsChoice::composite_operations as derive_kernels reports it, from
/// counts alone (the dynamics is not printed): to compare two derivations
/// before emitting one.
long composite_operations(kane::DerivationContext& products, ExpressionGraph& graph,
                          const ScalarType& scalar);

/// The code of `kernel` in `kernels`; throws std::logic_error if it is missing.
const KernelCode& find_kernel(const std::vector<KernelCode>& kernels, Kernel kernel);

}  // namespace kanegen::codegen
