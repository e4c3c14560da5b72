// SPDX-License-Identifier: GPL-2.0-or-later
// Prints the pieces of generated code that every kernel has, from its entry
// in the kernel table: the declaration, the definition, the forwarder in the
// model's `System` and its entry in the function-pointer table that the
// runtime consumes (kernel_table<Table>()).
#pragma once

#include <string>
#include <vector>

#include "codegen/kernel_table.hpp"
#include "codegen/scalar_type.hpp"

namespace kanegen::codegen {

/// A kernel's body as the derivation made it.
struct KernelCode {
  Kernel kernel{};
  std::string body;        ///< statements, indented by two spaces
  long operations = 0;     ///< additions, multiplications, divisions and calls
  std::string count_note;  ///< after the count in the header, e.g. " (120 of them in LDL^T)"
};

/// "ret name(args)" broken before an argument where it would pass the column
/// limit, continuation lines aligned after the parenthesis.
std::string prototype(const std::string& head, const std::vector<std::string>& arguments,
                      const std::string& tail, const std::string& indent = "");

/// The documented declaration, ending in ";\n", in the floating-point type `scalar`.
std::string declaration(const KernelSignature& signature, const ScalarType& scalar = ScalarType());
/// The definition; arguments the body never names are [[maybe_unused]].
std::string definition(const KernelSignature& signature, const std::string& body,
                       const ScalarType& scalar = ScalarType());
/// The static member of `System` that calls the kernel of `model_name` (double only: the runtime's face).
std::string system_forwarder(const KernelSignature& signature, const std::string& model_name);
/// The statement of kernel_table<Table>() that stores the kernel, with the
/// Params argument passed as `const void*` (or `void*`).
std::string table_entry(const KernelSignature& signature);

/// Whether `name` occurs in `code` as a whole identifier.
bool names_identifier(const std::string& code, const std::string& name);

}  // namespace kanegen::codegen
