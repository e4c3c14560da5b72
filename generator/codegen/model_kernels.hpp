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

/// In kernel-table order; the Jacobian kernels only with `jacobians`, the
/// quadratic controller kernels only with `controller` (which needs
/// `jacobians`); the bodies in the floating-point type `scalar`.
std::vector<KernelCode> derive_kernels(const model::Model& model, const kane::Equations& equations,
                                       const symbolic::Variables& vars, ExpressionGraph& graph,
                                       bool jacobians = false, bool controller = false,
                                       const ScalarType& scalar = ScalarType());

/// The code of `kernel` in `kernels`; throws std::logic_error if it is missing.
const KernelCode& find_kernel(const std::vector<KernelCode>& kernels, Kernel kernel);

}  // namespace kanegen::codegen
