// SPDX-License-Identifier: GPL-2.0-or-later
// The kernel table: every function a generated model has, with its C++
// signature, its documentation and where it appears, read from the one
// typed spec that the runtime shares (kanegen/runtime/kernels.def). The
// derivation (codegen/model_kernels.*) gives each kernel its body; the
// printer (codegen/kernel_printer.*) makes the declaration, the definition,
// the System forwarder and the runtime's function-pointer entry from this
// table.
#pragma once

#include <string>
#include <vector>

#include "kanegen/runtime/kernel_spec.hpp"

namespace kanegen::codegen {

/// Every kernel, in the order it is declared and defined (the spec's enum).
using Kernel = runtime::Kernel;

/// Which models have a kernel (the spec's rule: every model, closed loops,
/// --jacobians, both, or --controller).
using Presence = runtime::KernelPresence;

/// Whether a model with (or without) loops, generated with (or without)
/// Jacobians and controller kernels, has a kernel of this presence.
bool present(Presence presence, bool loops, bool jacobians, bool controller = false);

struct KernelArgument {
  std::string type;  ///< e.g. "const double*"
  std::string name;  ///< e.g. "q"
};

struct KernelSignature {
  Kernel kernel;
  const char* name;                       ///< the C++ function name
  const char* returns;                    ///< "void", "int", "double" or "bool"
  std::vector<KernelArgument> arguments;  ///< "const Params& p" first, if it takes Params
  const char* doc;  ///< the declaration's comment, "///" lines without the final newline
  Presence presence;
  bool counted;  ///< its operation count is listed in the header
  /// The runtime's Model calls it through kanegen/runtime/model_table.hpp,
  /// which then has a member of this name.
  bool in_runtime_table;
};

/// The table entry of a kernel.
const KernelSignature& signature(Kernel kernel);
/// All entries, in declaration order.
const std::vector<KernelSignature>& kernel_table();
/// The arguments of a signature, Params first.
const std::vector<KernelArgument>& arguments(const KernelSignature& signature);

}  // namespace kanegen::codegen
