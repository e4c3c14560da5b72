// SPDX-License-Identifier: GPL-2.0-or-later
// Splits a long straight-line kernel into functions of a bounded number of
// statements, so that the C++ compiler's time grows linearly with the model:
// g++'s time on one huge basic block (scheduling, register allocation) grows
// faster than its length. The parts are [[gnu::noinline]] static members of
// a local struct, called in order; a temporary read by a later part than
// the one that defines it passes through a workspace array on the caller's
// stack (slots are reused once no later part reads them), so the kernel
// still never allocates.
#pragma once

#include <string>
#include <vector>

#include "codegen/cpp_printer.hpp"
#include "codegen/kernel_table.hpp"
#include "codegen/scalar_type.hpp"

namespace kanegen::codegen {

/// The default of `kanegen generate --split-threshold`: kernels of more
/// operations are split (small models keep one function per kernel).
constexpr int kDefaultSplitThreshold = 6000;
/// Operations per part at most, about: g++ -O2 spends about as much time per
/// operation on parts of 300 to 3000 (chain20: 5.7 s for parts of 1000 and 6.4 s
/// for 3000, against 17 s unsplit).
constexpr long kPartOperations = 1000;

struct SplitBody {
  std::string body;      ///< the kernel's statements, split or `printed.body` unchanged
  int parts = 1;         ///< 1: not split
  long stack_bytes = 0;  ///< size of the workspace array
  /// " [split in N functions, B bytes of stack between them]" or "".
  std::string note() const;
};

/// `printed` (printed with the indent "  ") as the body of the kernel
/// `signature`: unchanged when its statements have at most `threshold`
/// operations or `threshold` <= 0, or when a statement reads a name that is
/// not one of the kernel's arguments (a local of the caller); otherwise in
/// parts of about min(threshold, kPartOperations) operations. `arrays`:
/// locals of the kernel that the parts may write through like arguments
/// (e.g. {"double*", "Ms"}). Assignments to any other target that is not an
/// argument (a local such as "const double m0_0" or "T") are made after the calls.
SplitBody split_kernel(const PrintedKernel& printed, const KernelSignature& signature,
                       const ScalarType& scalar, int threshold,
                       const std::vector<KernelArgument>& arrays = {});

}  // namespace kanegen::codegen
