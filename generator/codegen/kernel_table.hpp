// SPDX-License-Identifier: GPL-2.0-or-later
// The kernel table: every function a generated model has, declared once with
// its C++ signature, its documentation and where it appears. The derivation
// (codegen/model_kernels.*) gives each kernel its body; the printer
// (codegen/kernel_printer.*) makes the declaration, the definition, the
// System forwarder and the runtime's function-pointer entry from this table,
// so a new kernel is one entry here plus its derivation.
#pragma once

#include <string>
#include <vector>

namespace kanegen::codegen {

/// Every kernel, in the order it is declared and defined.
enum class Kernel {
  set_parameter,
  get_parameter,
  initial_state,
  mass_matrix,
  forcing,
  forward_dynamics,
  coordinate_rates,
  kinetic_energy,
  potential_energy,
  nonconservative_power,
  generalized_momentum,
  outputs,
  inverse_dynamics,
  gravity,
  constraints,
  constraint_jacobian,
  constraint_bias,
  constrained_dynamics,
  forcing_jacobian,
  mass_matrix_product_jacobian,
  constraint_force_jacobian,
  coriolis_matrix,
  output_jacobian,
  output_jacobian_rate,
  linearize,
};

/// Which models have a kernel: the Jacobians only those generated with
/// them (an option, for implicit integration), and of those the loop one
/// only closed loops; the quadratic controller kernels only those generated
/// with --controller (which brings the Jacobians too: linearize calls them).
enum class Presence { always, with_loops, with_jacobians, with_loops_and_jacobians, with_controller };

/// Whether a model with (or without) loops, generated with (or without)
/// Jacobians and controller kernels, has a kernel of this presence.
bool present(Presence presence, bool loops, bool jacobians, bool controller = false);

struct KernelArgument {
  std::string type;  ///< e.g. "const double*"
  std::string name;  ///< e.g. "q"
};

struct KernelSignature {
  Kernel kernel;
  const char* name;       ///< the C++ function name
  const char* returns;    ///< "void", "int", "double" or "bool"
  const char* arguments;  ///< "const Params& p, const double* q, double* M"
  const char* doc;        ///< the declaration's comment, "///" lines without the final newline
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
/// The arguments of a signature, split at the commas.
std::vector<KernelArgument> arguments(const KernelSignature& signature);

}  // namespace kanegen::codegen
