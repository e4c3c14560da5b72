// SPDX-License-Identifier: GPL-2.0-or-later
// The order in which a kernel's statements are emitted. Compilers do not
// reorder straight-line floating-point code much before register allocation
// (GCC's pre-allocation scheduler is off on x86 at -O2, and when on it made
// the kernels slower), so the emitted order decides how many values are
// live at once, and with it the spills to the stack. A statement is placed
// where it ends the most live ranges: of the statements whose operands are
// all computed, the one that reads the most values for the last time, less
// the one it defines, comes first; ties keep the printer's order.
#pragma once

#include <vector>

namespace kanegen::codegen {

struct OrderedStatement {
  std::vector<int> reads;  ///< the statements whose values it reads, without repeats
  bool defines = false;    ///< it defines a value that statements read
};

/// A topological order of `statements` (indices), as above. Deterministic:
/// it depends on the statements and their order only.
std::vector<int> shorten_live_ranges(const std::vector<OrderedStatement>& statements);

}  // namespace kanegen::codegen
