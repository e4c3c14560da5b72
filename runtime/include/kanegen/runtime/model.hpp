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

  bool set_parameter(const char* name, double value);  ///< false if unknown
  double parameter(int index) const { return table_.get_parameter(params(), index); }
  void mass_matrix(const double* q, double* M) const { table_.mass_matrix(params(), q, M); }
  void forcing(double t, const double* q, const double* u, const double* tau, double* f) const {
    table_.forcing(params(), t, q, u, tau, f);
  }
  /// 0 on success, k > 0 if the k-th pivot of the mass matrix was not positive.
  int forward_dynamics(double t, const double* q, const double* u, const double* tau, double* udot) const {
    return table_.forward_dynamics(params(), t, q, u, tau, udot);
  }
  void coordinate_rates(const double* q, const double* u, double* qdot) const {
    table_.coordinate_rates(q, u, qdot);
  }
  double kinetic_energy(const double* q, const double* u) const {
    return table_.kinetic_energy(params(), q, u);
  }
  double potential_energy(const double* q) const { return table_.potential_energy(params(), q); }
  bool has_nonconservative_power() const { return table_.nonconservative_power != nullptr; }
  /// The power of the non-conservative forces (the kernel's doc), without
  /// the drivers of prescribed motions; 0 for a table without the kernel.
  double nonconservative_power(double t, const double* q, const double* u, const double* tau) const {
    return table_.nonconservative_power ? table_.nonconservative_power(params(), t, q, u, tau) : 0.0;
  }
  void outputs(double t, const double* q, const double* u, double* y) const {
    table_.outputs(params(), t, q, u, y);
  }
  // For controllers; present in every table written by this kanegen (has_inverse_dynamics()).
  bool has_inverse_dynamics() const { return table_.inverse_dynamics && table_.gravity; }
  /// tau: nu, M udot - f with the inputs 0.
  void inverse_dynamics(double t, const double* q, const double* u, const double* udot, double* tau) const {
    table_.inverse_dynamics(params(), t, q, u, udot, tau);
  }
  /// g: nu, the generalized gravity forces.
  void gravity(const double* q, double* g) const { table_.gravity(params(), q, g); }
  /// The initial state for the current parameters (a prescribed coordinate
  /// starts where its motion does); info().q0, u0 hold it for the defaults.
  void initial_state(double* q, double* u) const;

  // Closed loops (info().nc > 0; no-ops for an open tree).
  /// phi: nc, the loop-closure residuals.
  void constraints(const double* q, double* phi) const {
    if (table_.constraints) table_.constraints(params(), q, phi);
  }
  /// C: nc*nu, row-major, dPhi/dq.
  void constraint_jacobian(const double* q, double* C) const {
    if (table_.constraint_jacobian) table_.constraint_jacobian(params(), q, C);
  }
  /// gamma: nc, the acceleration-level right-hand side, C udot = gamma = -(dC/dt) u.
  void constraint_bias(const double* q, const double* u, double* gamma) const {
    if (table_.constraint_bias) table_.constraint_bias(params(), q, u, gamma);
  }
  /// udot: nu, lambda: nc; as forward_dynamics, and -k for a singular
  /// configuration (nearly dependent loop equations).
  int constrained_dynamics(double t, const double* q, const double* u, const double* tau, double* udot,
                           double* lambda) const {
    if (!table_.constrained_dynamics) return forward_dynamics(t, q, u, tau, udot);
    return table_.constrained_dynamics(params(), t, q, u, tau, udot, lambda);
  }

  // Jacobians for implicit integration (see model_table.hpp); present only
  // in models generated with them (has_jacobians()).
  bool has_jacobians() const {
    return table_.forcing_jacobian && table_.mass_matrix_product_jacobian &&
           (table_.nc == 0 || table_.constraint_force_jacobian);
  }
  /// dfdq: nu*nq, dfdu: nu*nu, row-major.
  void forcing_jacobian(double t, const double* q, const double* u, const double* tau, double* dfdq,
                        double* dfdu) const {
    table_.forcing_jacobian(params(), t, q, u, tau, dfdq, dfdu);
  }
  /// dMa_dq: nu*nq, d(M(q) a)/dq.
  void mass_matrix_product_jacobian(const double* q, const double* a, double* dMa_dq) const {
    table_.mass_matrix_product_jacobian(params(), q, a, dMa_dq);
  }
  /// dCl_dq: nu*nq, d(C(q)^T lambda)/dq (closed loops).
  void constraint_force_jacobian(const double* q, const double* lambda, double* dCl_dq) const {
    table_.constraint_force_jacobian(params(), q, lambda, dCl_dq);
  }

  // The quadratic controller kernels (models generated with --controller; has_controller()).
  bool has_controller() const {
    return table_.coriolis_matrix && table_.output_jacobian && table_.output_jacobian_rate &&
           table_.linearize;
  }
  /// C: nu*nu, row-major.
  void coriolis_matrix(const double* q, const double* u, double* C) const {
    table_.coriolis_matrix(params(), q, u, C);
  }
  /// J: ny*nu, row-major.
  void output_jacobian(double t, const double* q, double* J) const {
    table_.output_jacobian(params(), t, q, J);
  }
  /// Jdot_u: ny.
  void output_jacobian_rate(double t, const double* q, const double* u, double* Jdot_u) const {
    table_.output_jacobian_rate(params(), t, q, u, Jdot_u);
  }
  /// A: 2nu*2nu, B: 2nu*ntau, row-major; 0, or k > 0 for a non-positive pivot of M.
  int linearize(double t, const double* q, const double* u, const double* tau, double* A, double* B) const {
    return table_.linearize(params(), t, q, u, tau, A, B);
  }

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
