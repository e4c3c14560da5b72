// SPDX-License-Identifier: MIT
#include "kanegen/runtime/model.hpp"

#include <stdexcept>
#include <string>

namespace kanegen::runtime {
namespace {

/// The kernels that every model has; the loop kernels may be null.
void check_complete(const ModelTable& t) {
  const bool complete = t.name && t.default_parameters && t.set_parameter && t.get_parameter &&
                        t.initial_state && t.mass_matrix && t.forcing && t.forward_dynamics &&
                        t.coordinate_rates && t.kinetic_energy && t.potential_energy && t.outputs;
  const bool loops_complete =
      t.nc == 0 || (t.constraints && t.constraint_jacobian && t.constraint_bias && t.constrained_dynamics);
  if (!complete || !loops_complete)
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

bool Model::set_parameter(const char* name, double value) {
  return table_.set_parameter(parameters_.data(), name, value);
}

void Model::initial_state(double* q, double* u) const { table_.initial_state(params(), q, u); }

}  // namespace kanegen::runtime
