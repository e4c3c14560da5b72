// SPDX-License-Identifier: MIT
// Fixed-step generalized-alpha integration for real time and
// hardware-in-the-loop: Chung and Hulbert's parameters from the spectral
// radius at infinity, in Arnold and Bruls's form for constrained systems
// (index 3: Phi(q_n+1) = 0 is one of the Newton equations), with Newton
// iteration matrices from the generated Jacobian kernels, a bounded number
// of Newton iterations per step and no allocation after construction.
// docs/runtime.md describes the method and what it guarantees.
#pragma once

#include <string>
#include <vector>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

struct GenAlphaOptions {
  double h = 1e-3;  ///< the fixed step (s)
  /// Spectral radius at infinity, in [0, 1]: 1 keeps every frequency
  /// (no numerical damping, energy conserved for linear systems), 0 damps
  /// the unresolved ones in one step. 0.8 damps modes with omega h >> 1
  /// (a beam's axial modes at a step of the motion) while resolved modes
  /// get an algorithmic damping ratio of only O((omega h)^3).
  double rho_inf = 0.8;
  int max_newton = 10;  ///< Newton iterations per step, at most (the real-time bound)
  /// Newton stops when the estimated error of the iterate (Hairer's
  /// theta / (1 - theta) times the last increment) is below `tolerance`
  /// relative to 1 + |x| in the RMS over the free coordinates and speeds.
  /// 1e-10: 1e-8 left N four-bar's crank 7e-6 rad off after 10 s at 1 ms
  /// (2.7e-6 with 1e-10); the spin-up beam needs no more iterations for it.
  double tolerance = 1e-10;
  /// ...and every |Phi_i(q)| <= constraint_tolerance (closed loops).
  double constraint_tolerance = 1e-11;
  /// Simplified Newton: keep the factored iteration matrix from step to
  /// step, re-evaluating the Jacobians only when Newton contracts slowly
  /// (rate above 0.5 or half of max_newton spent within a step, or a rate
  /// above 0.1 in the previous step).
  /// false: fresh Jacobians and a new factorization at every step.
  bool reuse_jacobian = true;
};

/// Counters since construction (start() does not reset them).
struct ImplicitStats {
  long steps = 0;                 ///< accepted steps
  long rejected = 0;              ///< failed steps (a fixed-step method does not retry)
  long newton_iterations = 0;     ///< linear solves with the iteration matrix
  long jacobian_evaluations = 0;  ///< evaluations of the three Jacobian kernels
  long factorizations = 0;        ///< LU factorizations of the iteration matrix
};

/// Chung-Hulbert parameters for a spectral radius at infinity rho_inf:
/// alpha_m = (2 rho - 1) / (rho + 1), alpha_f = rho / (rho + 1),
/// gamma = 1/2 + alpha_f - alpha_m, beta = (gamma + 1/2)^2 / 4.
struct GenAlphaCoefficients {
  double alpha_m, alpha_f, gamma, beta;
};
GenAlphaCoefficients genalpha_coefficients(double rho_inf);

/// Integrates M(q) u_dot = f(t, q, u, tau) + C(q)^T lambda, Phi(q) = 0,
/// q_dot = u with a fixed step. Usage:
///
///     GenAlpha ga(model, options);           // allocates its workspace
///     if (!ga.start(t0, q0, u0, tau, &why)) ...  // no allocation on success
///     while (ga.t() < t_end)
///       if (!ga.step(tau, &why)) ...         // no allocation on success
///
/// Prescribed coordinates (info().coordinate_roles == 2; open trees, which
/// have no roles, are probed, see detect_prescribed) follow their given
/// acceleration, which forward_dynamics reports, as in the explicit
/// methods. The model must have been generated with Jacobians.
class GenAlpha {
 public:
  /// Throws std::invalid_argument if the options are out of range or the
  /// model has no Jacobian kernels (regenerate it with --jacobians).
  GenAlpha(const Model& model, const GenAlphaOptions& options);

  /// Starts at (t0, q, u): q must close the loops (|Phi| <= 1e-10, e.g.
  /// from LoopSolver::assemble); u is corrected to C u = 0 (least kinetic
  /// energy). The initial acceleration comes from constrained_dynamics.
  /// tau: ntau inputs, or null for all zero.
  /// False, with the reason in *why (if not null), otherwise. Allocates
  /// nothing unless it fails.
  bool start(double t0, const double* q, const double* u, const double* tau, std::string* why);

  /// One step to t() + h with the inputs `tau` (held over the step; ntau
  /// values, or null for all zero). False, with the time and the reason in
  /// *why, if Newton does not converge within max_newton iterations, the
  /// iteration matrix is singular or the state is not finite; the state is
  /// then left at the last good step. Allocates nothing unless it fails.
  bool step(const double* tau, std::string* why);

  double t() const { return t0_ + static_cast<double>(n_) * opt_.h; }
  const double* q() const { return q_.data(); }         ///< nq
  const double* u() const { return u_.data(); }         ///< nu
  const double* udot() const { return vd_.data(); }     ///< nu, the acceleration at t()
  const double* lambda() const { return lam_.data(); }  ///< nc, the loop multipliers at t()
  const ImplicitStats& stats() const { return stats_; }
  /// Whether coordinate i follows a prescribed motion (not solved for).
  bool prescribed(int i) const { return prescribed_[static_cast<size_t>(i)] != 0; }
  const GenAlphaOptions& options() const { return opt_; }

 private:
  /// Generated open trees carry no coordinate_roles: a coordinate is prescribed if
  /// forward_dynamics leaves its row of M u_dot = f unsolved (the residual
  /// is the driving force) at two generic states. Allocates (constructor only).
  void detect_prescribed();
  /// The trial state at t1 from the committed one, with the acceleration
  /// of the last step as the guess (the given one for prescribed speeds).
  void predict(double t1, const double* tau);
  /// The residuals at the trial state. Closed loops: rhs_ = -(the
  /// residuals), with M_, f_, C_ evaluated there. Open trees (fused_): one
  /// forward_dynamics call, f_ = M^-1 f - udot, which weight_residual()
  /// turns into rhs_. False, with the reason, if forward_dynamics fails.
  bool residual(double t1, const double* tau, std::string* reason);
  /// Open trees: rhs_ = M f_ with the M of the last refresh(); else nothing.
  void weight_residual();
  /// Jacobians at the trial state, the iteration matrix, its LU factors.
  bool refresh(double t1, const double* tau);
  /// Newton on the trial state; false, with the reason, if it fails.
  bool newton(double t1, const double* tau, std::string* reason);
  /// The Newton update from the solution in rhs_; returns its weighted norm.
  double apply_increment();
  /// Largest |Phi_i(q)| (NaN if one is NaN); 0 for an open tree.
  double constraint_residual(const double* q);
  /// u corrected to C(q) u = 0 by the change of least kinetic energy.
  bool correct_speeds(const double* q, double* u, std::string* reason);
  bool fail(const std::string& reason, std::string* why);
  /// "[q1=..., ..., u1=..., ...]" of the committed state, for messages.
  std::string state() const;

  const Model& model_;
  GenAlphaOptions opt_;
  GenAlphaCoefficients c_;
  int n_dof_, nc_, dim_;  ///< nu, nc, nu + nc
  /// Open trees: the residual from forward_dynamics (M and f in one kernel
  /// that exploits their structure) instead of mass_matrix, forcing and a
  /// dense product; closed loops need C^T lambda, which it does not give.
  bool fused_ = false;
  double beta_p_, gamma_p_;  ///< beta' = (1 - alpha_m) / (h^2 beta (1 - alpha_f)), gamma' = gamma / (h beta)
  std::vector<char> prescribed_;
  std::vector<int> free_;
  bool any_prescribed_ = false;

  // Committed state at t(): q, u, acceleration, auxiliary acceleration a, lambda.
  double t0_ = 0.0;
  long n_ = 0;
  bool started_ = false;
  std::vector<double> q_, u_, vd_, a_, lam_;
  // The step's trial state at t() + h.
  std::vector<double> q1_, u1_, vd1_, a1_, lam1_;

  // Workspace, all sized in the constructor.
  std::vector<double> M_, f_, C_, phi_, rhs_;
  std::vector<double> dfdq_, dfdu_, dMa_, dCl_;
  std::vector<double> lu_;   ///< the iteration matrix, dim_ x dim_, then its LU factors
  std::vector<double> lut_;  ///< the LU factors transposed, for the solves
  std::vector<int> pivots_;
  std::vector<int> lu_upper_begin_, lu_lower_end_;  ///< nonzero ranges of the factors' columns
  std::vector<int> mass_begin_, mass_end_;          ///< open trees: nonzero ranges of M_'s rows
  std::vector<double> given_, given_lambda_;  ///< forward_dynamics output for the prescribed accelerations
  std::vector<double> chol_, w_, g_, y_;      ///< speed correction: chol(M_ff), M_ff^-1 C^T, C M^-1 C^T
  std::vector<char> used_;
  std::vector<double> no_inputs_;  ///< ntau zeros, for tau == nullptr
  bool factored_ = false;
  bool refresh_next_ = false;
  double eta_ =
      1.0;  ///< theta / (1 - theta) of the last step's first iteration, for the next step's first test
  ImplicitStats stats_;
};

}  // namespace kanegen::runtime
