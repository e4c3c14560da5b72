// SPDX-License-Identifier: MIT
// The Jacobian of a model's state equations, x = (q, u),
//   q' = u,   u' = a(t, q, u)   (forward_dynamics or constrained_dynamics),
// from the model's generated Jacobian kernels, for the implicit integrators'
// Newton iteration. Never by finite differences.
#pragma once

#include <string>
#include <vector>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

/// Why `model` cannot be integrated implicitly (it was generated without
/// Jacobian kernels), with what to do about it.
std::string missing_jacobians_message(const ModelInfo& info);

/// The coordinates whose acceleration is prescribed: info().coordinate_roles
/// == 2 where the table has roles (closed loops). Generated open trees carry
/// no roles, so there they are found by their defining property: an
/// acceleration that forward_dynamics returns unchanged (bit for bit) when
/// every coordinate and speed of the initial state is perturbed. A free
/// coordinate whose acceleration truly never depends on the state is
/// classified with them, which is harmless: its Jacobian row is zero either
/// way, and the free block's rows stay exact. Empty vector: none.
std::vector<char> prescribed_coordinates(const Model& model);

/// J = d(x')/dx = [[0, I], [da/dq, da/du]], n = nq + nu (q' = u in every
/// generated model, so nq == nu).
///
///  - Open trees: M a = f gives da/dq = M^-1 (df/dq - d(M a)/dq), da/du =
///    M^-1 df/du, exact.
///  - Prescribed coordinates (prescribed_coordinates): their accelerations depend on t
///    only, so their rows are zero; the free rows use the free block M_FF
///    (the prescribed accelerations enter d(M a)/dq through a).
///  - Closed loops: M a = f + C^T lambda, C a = gamma. The rows are
///    P M^-1 (df/dq - d(M a)/dq + d(C^T lambda)/dq) and P M^-1 df/du, with
///    P = I - M^-1 C^T (C M^-1 C^T)^+ C the M-orthogonal projector onto
///    C delta = 0. This drops the derivatives of gamma and of C itself in
///    C a = gamma: an approximation, fine for Newton's iteration matrix (the
///    projection after each step keeps the motion on the constraints), and
///    exact for the stiff elastic terms, which are in df/dq. Dependent loop
///    equations (a parallelogram) are skipped in (C M^-1 C^T)^+.
class StateJacobian {
 public:
  /// Throws std::invalid_argument (missing_jacobians_message) if the model
  /// has no Jacobian kernels.
  explicit StateJacobian(const Model& model);

  /// J: n*n, row-major, at (t, x) with the inputs tau (ntau values; may be
  /// null if ntau == 0). False if the mass matrix is not positive definite
  /// there. Allocates nothing, except at a singular position of the loops,
  /// where udot and lambda come from LoopSolver::dynamics's fallbacks.
  bool evaluate(double t, const double* x, const double* tau, double* J);

 private:
  bool accelerations(double t, const double* q, const double* u, const double* tau);
  bool factor_mass_block(const double* q);
  void solve_mass_block(double* v) const;  ///< v (free-block size) := M_FF^-1 v
  void project_columns();                  ///< Y := P Y (closed loops)
  bool factor_gram();

  const Model& model_;
  int m_, nc_, nf_;
  std::vector<int> free_;  ///< the coordinates that are not prescribed
  std::vector<double> udot_, lambda_, tau0_, dfdq_, dfdu_, dMa_, dCl_, M_, L_;
  std::vector<double> Y_;  ///< nf x 2m: the free rows of [da/dq, da/du]
  std::vector<double> C_, W_, G_, z_;
  std::vector<char> used_;  ///< the loop equations kept in (C M^-1 C^T)^+
};

}  // namespace kanegen::runtime
