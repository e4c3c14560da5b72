// SPDX-License-Identifier: GPL-2.0-or-later
// M udot = f solved by an LDL^T unrolled for one model's sparsity.
#pragma once

#include <string>
#include <vector>

#include "codegen/scalar_type.hpp"

namespace kanegen::codegen {

struct UnrolledLdlt {
  std::string text;     ///< statements, indented by two spaces
  long operations = 0;  ///< additions, multiplications and divisions
};

/// The solve over the speeds `solved` (those not prescribed): the entries of
/// M are locals m<i>_<j> (i >= j, indices into `solved`), udot holds the
/// right-hand side on entry; `nonzero_m` (row-major, ns*ns) marks the
/// entries that are not zero by the tree's structure, and entries that stay
/// zero in L are left out. Returns k from the kernel when pivot k is not
/// positive. The locals are of type `scalar`.
UnrolledLdlt unrolled_ldlt(const std::vector<bool>& nonzero_m, const std::vector<int>& solved,
                           const ScalarType& scalar);
/// unrolled_ldlt's operation count alone, without its text.
long unrolled_ldlt_operations(const std::vector<bool>& nonzero_m, const std::vector<int>& solved);

}  // namespace kanegen::codegen
