// SPDX-License-Identifier: MIT
// The kernels of one generated model as plain function pointers: what the
// generated `kernel_table<kanegen::runtime::ModelTable>()` fills in (see the
// generated header), so that everything in the runner that does not depend
// on the model is compiled once, in the runtime library. Every kernel takes
// the model's Params as an untyped pointer.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>

namespace kanegen::runtime {

struct ModelTable {
  // Sizes, names and the default initial state.
  const char* name = nullptr;
  int nq = 0, nu = 0, ntau = 0, ny = 0, np = 0;
  const char* const* coordinate_names = nullptr;
  const char* const* speed_names = nullptr;
  const char* const* input_names = nullptr;
  const char* const* output_names = nullptr;
  const char* const* parameter_names = nullptr;
  const double* q0 = nullptr;
  const double* u0 = nullptr;
  /// Per coordinate (nq): its joint ("" for an elastic coordinate) and the
  /// bodies it moves, moved_bodies[moved_bodies_first[i] .. moved_bodies_first[i + 1]);
  /// null in tables written without them.
  const char* const* coordinate_joints = nullptr;
  const int* moved_bodies_first = nullptr;
  const char* const* moved_bodies = nullptr;
  /// Forces not from a potential other than the inputs (nonconservative_power
  /// not 0 at tau = 0), or prescribed motions.
  bool nonconservative = false;
  // Closed loops (0 and null for an open tree).
  int nc = 0;
  const char* const* constraint_names = nullptr;
  const int* coordinate_roles = nullptr;  ///< nq: 0 free, 1 marked independent, 2 prescribed

  /// The size of Params, and its default construction in storage of that size.
  std::size_t parameters_size = 0;
  void (*default_parameters)(void* p) = nullptr;

  /// The default P in the storage p, for a generated kernel_table's
  /// default_parameters (here, so that the generated header includes nothing).
  template <class P>
  static void construct_parameters(void* p) {
    static_assert(std::is_trivially_copyable<P>::value && alignof(P) <= alignof(double),
                  "the runtime keeps Params in storage of doubles");
    new (p) P();
  }

  // The kernels (the generated header documents each).
  bool (*set_parameter)(void* p, const char* name, double value) = nullptr;
  double (*get_parameter)(const void* p, int i) = nullptr;
  void (*initial_state)(const void* p, double* q, double* u) = nullptr;
  void (*mass_matrix)(const void* p, const double* q, double* M) = nullptr;
  void (*forcing)(const void* p, double t, const double* q, const double* u, const double* tau,
                  double* f) = nullptr;
  int (*forward_dynamics)(const void* p, double t, const double* q, const double* u, const double* tau,
                          double* udot) = nullptr;
  void (*coordinate_rates)(const double* q, const double* u, double* qdot) = nullptr;
  double (*kinetic_energy)(const void* p, const double* q, const double* u) = nullptr;
  double (*potential_energy)(const void* p, const double* q) = nullptr;
  double (*nonconservative_power)(const void* p, double t, const double* q, const double* u,
                                  const double* tau) = nullptr;
  void (*outputs)(const void* p, double t, const double* q, const double* u, double* y) = nullptr;
  // For controllers (null in tables written before they were in the table).
  /// tau: nu, M udot - f with the inputs 0 (the generated header documents it).
  void (*inverse_dynamics)(const void* p, double t, const double* q, const double* u, const double* udot,
                           double* tau) = nullptr;
  /// g: nu, the generalized gravity forces dV_gravity/dq.
  void (*gravity)(const void* p, const double* q, double* g) = nullptr;
  // Closed loops only (null for an open tree).
  void (*constraints)(const void* p, const double* q, double* phi) = nullptr;
  void (*constraint_jacobian)(const void* p, const double* q, double* C) = nullptr;
  void (*constraint_bias)(const void* p, const double* q, const double* u, double* gamma) = nullptr;
  int (*constrained_dynamics)(const void* p, double t, const double* q, const double* u, const double* tau,
                              double* udot, double* lambda) = nullptr;
  // Jacobians for implicit integration (models generated with jacobians;
  // null otherwise). Row-major; q_dot = u in every generated model.
  /// dfdq: nu*nq, dfdu: nu*nu, the partial derivatives of forcing.
  void (*forcing_jacobian)(const void* p, double t, const double* q, const double* u, const double* tau,
                           double* dfdq, double* dfdu) = nullptr;
  /// dMa_dq: nu*nq, d(M(q) a)/dq for a fixed vector a (nu).
  void (*mass_matrix_product_jacobian)(const void* p, const double* q, const double* a,
                                       double* dMa_dq) = nullptr;
  /// dCl_dq: nu*nq, d(C(q)^T lambda)/dq for fixed lambda (nc); closed loops only.
  void (*constraint_force_jacobian)(const void* p, const double* q, const double* lambda,
                                    double* dCl_dq) = nullptr;
  // The quadratic controller kernels (models generated with --controller;
  // null otherwise). Row-major.
  /// C: nu*nu, Mdot - 2C skew-symmetric.
  void (*coriolis_matrix)(const void* p, const double* q, const double* u, double* C) = nullptr;
  /// J: ny*nu, d(outputs)/dq.
  void (*output_jacobian)(const void* p, double t, const double* q, double* J) = nullptr;
  /// Jdot_u: ny, (dJ/dt) u.
  void (*output_jacobian_rate)(const void* p, double t, const double* q, const double* u,
                               double* Jdot_u) = nullptr;
  /// A: 2nu*2nu, B: 2nu*ntau; returns 0 or k > 0 for a non-positive pivot of M.
  int (*linearize)(const void* p, double t, const double* q, const double* u, const double* tau, double* A,
                   double* B) = nullptr;
};

}  // namespace kanegen::runtime
