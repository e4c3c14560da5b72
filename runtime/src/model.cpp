// SPDX-License-Identifier: MIT
#include "kanegen/runtime/model.hpp"

#include <stdexcept>
#include <string>

namespace kanegen::runtime {
namespace {

/// Whether `table` holds `kernel` (false for one the table cannot hold).
bool bound(const ModelTable& table, Kernel kernel) {
  switch (kernel) {
#define KANEGEN_BOUND_required(name) \
  case Kernel::name:                 \
    return table.name != nullptr;
#define KANEGEN_BOUND_optional KANEGEN_BOUND_required
#define KANEGEN_BOUND_unbound(name) \
  case Kernel::name:                \
    return false;
#define KANEGEN_KERNEL(name, returns, params, arguments, presence, counted, binding, ...) \
  KANEGEN_BOUND_##binding(name)
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
#undef KANEGEN_BOUND_required
#undef KANEGEN_BOUND_optional
#undef KANEGEN_BOUND_unbound
  }
  return false;
}

/// Every bound kernel of `presence` is in the table (with loops: those of
/// loops too; none is asked of a presence a table of this kind lacks).
bool holds_all(const ModelTable& table, KernelPresence presence) {
  for (const KernelSpec& s : kernel_specs)
    if (s.binding != KernelBinding::unbound && s.presence == presence && !bound(table, s.kernel))
      return false;
  return true;
}

/// The kernels the spec requires of every table (and of a table with loops,
/// the loop kernels); the ones an option brings may be null.
void check_complete(const ModelTable& t) {
  bool complete = t.name && t.default_parameters;
  for (const KernelSpec& s : kernel_specs)
    if (s.binding == KernelBinding::required && kernel_present(s.presence, t.nc > 0, false, false))
      complete = complete && bound(t, s.kernel);
  if (!complete)
    throw std::invalid_argument(std::string("model table of ") + (t.name ? t.name : "(unnamed)") +
                                " lacks a kernel: regenerate the model with this kanegen");
}

}  // namespace

Model::Model(const ModelTable& table) : table_(table) {
  check_complete(table_);
  info_ = ModelInfo{table_.name,
                    table_.nq,
                    table_.nu,
                    table_.ntau,
                    table_.ny,
                    table_.np,
                    table_.coordinate_names,
                    table_.speed_names,
                    table_.input_names,
                    table_.output_names,
                    table_.parameter_names,
                    table_.q0,
                    table_.u0,
                    table_.nc,
                    table_.constraint_names,
                    table_.coordinate_roles,
                    table_.coordinate_joints,
                    table_.moved_bodies_first,
                    table_.moved_bodies,
                    table_.nonconservative};
  // Params is a struct of doubles: storage of doubles holds it aligned.
  parameters_.assign(table_.parameters_size / sizeof(double) + 1, 0.0);
  table_.default_parameters(parameters_.data());
}

bool Model::has(Kernel kernel) const { return bound(table_, kernel); }

bool Model::has_jacobians() const {
  return holds_all(table_, KernelPresence::with_jacobians) &&
         (table_.nc == 0 || holds_all(table_, KernelPresence::with_loops_and_jacobians));
}

bool Model::has_controller() const { return holds_all(table_, KernelPresence::with_controller); }

}  // namespace kanegen::runtime
