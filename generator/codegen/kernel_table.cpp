// SPDX-License-Identifier: GPL-2.0-or-later
#include "codegen/kernel_table.hpp"

#include <stdexcept>

namespace kanegen::codegen {
namespace {

/// The C++ type of an argument of each role, as the generated code spells it
/// (in double; ScalarType::in_type makes it float).
const char* type_of(runtime::ArgumentRole role) {
  switch (role) {
    case runtime::ArgumentRole::in:
      return "const double*";
    case runtime::ArgumentRole::out:
      return "double*";
    case runtime::ArgumentRole::scalar:
      return "double";
    case runtime::ArgumentRole::text:
      return "const char*";
    case runtime::ArgumentRole::index:
      return "int";
  }
  throw std::logic_error("unknown argument role");
}

KernelSignature from_spec(const runtime::KernelSpec& spec) {
  std::vector<KernelArgument> arguments;
  if (spec.params == runtime::ParamsAccess::read) arguments.push_back({"const Params&", "p"});
  if (spec.params == runtime::ParamsAccess::write) arguments.push_back({"Params&", "p"});
  for (std::size_t i = 0; i < spec.argument_count; ++i)
    arguments.push_back({type_of(spec.arguments[i].role), spec.arguments[i].name});
  return {spec.kernel, spec.name,     spec.returns, std::move(arguments),
          spec.doc,    spec.presence, spec.counted, spec.binding != runtime::KernelBinding::unbound};
}

std::vector<KernelSignature> from_specs() {
  std::vector<KernelSignature> table;
  for (const runtime::KernelSpec& spec : runtime::kernel_specs) table.push_back(from_spec(spec));
  return table;
}

}  // namespace

const std::vector<KernelSignature>& kernel_table() {
  static const std::vector<KernelSignature> table = from_specs();
  return table;
}

bool present(Presence presence, bool loops, bool jacobians, bool controller) {
  return runtime::kernel_present(presence, loops, jacobians, controller);
}

const KernelSignature& signature(Kernel kernel) {
  const std::vector<KernelSignature>& table = kernel_table();
  const std::size_t at = static_cast<std::size_t>(kernel);
  if (at >= table.size() || table[at].kernel != kernel)
    throw std::logic_error("kernel missing from the kernel table");
  return table[at];
}

const std::vector<KernelArgument>& arguments(const KernelSignature& signature) { return signature.arguments; }

}  // namespace kanegen::codegen
