// SPDX-License-Identifier: MIT
// A generated model together with one set of parameter values, called
// through its table of kernels (model_table.hpp), so that everything in the
// runner that does not depend on the particular model is compiled once in
// the runtime library instead of in every model's executable.
#pragma once

#include <vector>

#include "kanegen/runtime/model_table.hpp"

namespace kanegen::runtime {

/// Sizes, names and initial state of a model (pointers into generated code).
struct ModelInfo {
  const char* name;
  int nq, nu, ntau, ny, np;
  const char* const* coordinate_names;
  const char* const* speed_names;
  const char* const* input_names;
  const char* const* output_names;
  const char* const* parameter_names;
  const double* q0;
  const double* u0;
  /// Closed loops (0 and null for an open tree).
  int nc = 0;
  const char* const* constraint_names = nullptr;
  const int* coordinate_roles = nullptr;  ///< nq: 0 free, 1 marked independent, 2 prescribed
  /// Per coordinate: its joint and the bodies it moves (see ModelTable; may be null).
  const char* const* coordinate_joints = nullptr;
  const int* moved_bodies_first = nullptr;
  const char* const* moved_bodies = nullptr;
  /// Forces not from a potential other than the inputs: dampers, efforts,
  /// body-fixed forces, prescribed motions (see ModelTable).
  bool nonconservative = false;
};

/// The kernels of system.hpp with the parameters bound.
class Model {
 public:
  /// The model of `table` with its default parameters; throws
  /// std::invalid_argument if a kernel every model has is missing.
  explicit Model(const ModelTable& table);
  const ModelInfo& info() const { return info_; }

  // The kernels, one method each from kernels.def with the parameters bound
  // (the generated header documents each): a `call` forwards to the table, a
  // `call_or_zero` gives 0 (or does nothing) where the table has no entry
  // (the loop kernels of an open tree, a table without nonconservative_power);
  // set_parameter is not const. The others are written below.
#define KANEGEN_MODEL_CONST_read const
#define KANEGEN_MODEL_CONST_none const
#define KANEGEN_MODEL_CONST_write
#define KANEGEN_MODEL_PARAMS_read params(),
#define KANEGEN_MODEL_PARAMS_write parameters_.data(),
#define KANEGEN_MODEL_PARAMS_none
#define KANEGEN_MODEL_call(name, returns, params, arguments)                                         \
  returns name(KANEGEN_MAP(KANEGEN_TYPED_ARGUMENT, arguments)) KANEGEN_MODEL_CONST_##params {        \
    return table_.name(KANEGEN_MODEL_PARAMS_##params KANEGEN_MAP(KANEGEN_ARGUMENT_NAME, arguments)); \
  }
#define KANEGEN_MODEL_call_or_zero(name, returns, params, arguments)                                 \
  returns name(KANEGEN_MAP(KANEGEN_TYPED_ARGUMENT, arguments)) KANEGEN_MODEL_CONST_##params {        \
    if (!table_.name) return returns();                                                              \
    return table_.name(KANEGEN_MODEL_PARAMS_##params KANEGEN_MAP(KANEGEN_ARGUMENT_NAME, arguments)); \
  }
#define KANEGEN_MODEL_by_hand(name, returns, params, arguments)
#define KANEGEN_MODEL_none(name, returns, params, arguments)
#define KANEGEN_KERNEL(name, returns, params, arguments, presence, counted, binding, wrapper, ...) \
  KANEGEN_MODEL_##wrapper(name, returns, params, arguments)
#include "kanegen/runtime/kernels.def"
#undef KANEGEN_KERNEL
#undef KANEGEN_MODEL_call
#undef KANEGEN_MODEL_call_or_zero
#undef KANEGEN_MODEL_by_hand
#undef KANEGEN_MODEL_none
#undef KANEGEN_MODEL_CONST_read
#undef KANEGEN_MODEL_CONST_none
#undef KANEGEN_MODEL_CONST_write
#undef KANEGEN_MODEL_PARAMS_read
#undef KANEGEN_MODEL_PARAMS_write
#undef KANEGEN_MODEL_PARAMS_none

  /// The parameter with index i in parameter_names order (the get_parameter kernel).
  double parameter(int index) const { return table_.get_parameter(params(), index); }
  /// udot: nu, lambda: nc; as forward_dynamics, and -k for a singular
  /// configuration (nearly dependent loop equations); forward_dynamics for an open tree.
  int constrained_dynamics(double t, const double* q, const double* u, const double* tau, double* udot,
                           double* lambda) const {
    if (!table_.constrained_dynamics) return forward_dynamics(t, q, u, tau, udot);
    return table_.constrained_dynamics(params(), t, q, u, tau, udot, lambda);
  }

  /// Whether the table holds nonconservative_power (tables written before it did not).
  bool has_nonconservative_power() const { return table_.nonconservative_power != nullptr; }
  /// inverse_dynamics and gravity: in every table written by this kanegen.
  bool has_inverse_dynamics() const { return table_.inverse_dynamics && table_.gravity; }
  /// The Jacobians for implicit integration (models generated with them;
  /// constraint_force_jacobian too with loops).
  bool has_jacobians() const;
  /// The quadratic controller kernels (models generated with --controller).
  bool has_controller() const;
  /// Whether the table holds `kernel` (false for a kernel it cannot hold).
  bool has(Kernel kernel) const;
  /// The table, and the Params storage the methods bind: for a caller that
  /// calls a kernel by its spec (kernel_thunks.hpp; the runner's batch command).
  const ModelTable& table() const { return table_; }
  const void* parameter_storage() const { return params(); }

 private:
  const void* params() const { return parameters_.data(); }

  ModelTable table_;
  ModelInfo info_;
  std::vector<double> parameters_;  ///< storage of the model's Params (plain doubles)
};

/// The Model of a generated System (System::kernel_table), with its default parameters.
template <class System>
Model make_model() {
  return Model(System::template kernel_table<ModelTable>());
}

}  // namespace kanegen::runtime
