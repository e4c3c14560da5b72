// SPDX-License-Identifier: MIT
// The types every integrator shares: the right-hand side, Jacobian and
// observer callbacks, the options, the step statistics and the result. No
// functions: the methods (runtime/src) and the registry (methods.hpp) sit on
// top of these, and integrate() (integrators.hpp) on top of the registry.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace kanegen::runtime {

/// x' = f(t, x). Returns false if f cannot be evaluated at (t, x), which
/// stops the integration with Status::kRhsFailed.
using Rhs = std::function<bool(double t, const double* x, double* xdot)>;
/// J = d(xdot)/dx at (t, x), n*n row-major, for the implicit method. It only
/// drives Newton's iteration (its accuracy affects convergence, not the
/// result). Returns false if it cannot be evaluated (the step is retried
/// with a smaller step size).
using Jacobian = std::function<bool(double t, const double* x, double* J)>;
/// Called at each output time with the state there; false stops the run.
using Observer = std::function<bool(double t, const double* x)>;

struct IntegrationOptions {
  double t_end = 1.0;
  double dt = 0.01;                        ///< output interval; also the RK4 step
  double rtol = 1e-8;                      ///< adaptive methods: relative tolerance, all components
  double atol = 1e-10;                     ///< adaptive methods: absolute tolerance, all components
  std::vector<double> atol_per_component;  ///< adaptive methods: overrides atol if non-empty (size n)
  double h0 = 0.0;                         ///< adaptive initial step; 0: estimated
  double h_min = 0.0;                      ///< adaptive: give up below this step; 0: round-off limit
  double h_max = 0.0;                      ///< adaptive: largest step; 0: t_end - t0
  long max_steps = 10000000;               ///< attempted steps (accepted + rejected) before giving up
  /// Implicit: the highest BDF order, 1 to 5. 2 by default: BDF1 and BDF2
  /// are A-stable and damp the unresolved, undamped modes of elastic links;
  /// orders 3 to 5 are unstable near the imaginary axis, where CVODE's
  /// stability-limit detection does not catch them (the spin-up beam takes
  /// 900000 steps at order 5, 3700 at order 2). Raise it for smooth,
  /// non-oscillatory problems at tight tolerances.
  int max_order = 2;
  double safety = 0.9;       ///< DOPRI5 step-size controller safety factor
  double min_factor = 0.2;   ///< DOPRI5: smallest step change per step
  double max_factor = 10.0;  ///< DOPRI5: largest step change per step
  double pi_beta = 0.04;     ///< DOPRI5 PI controller gain (Hairer's beta); 0: plain I controller
  /// Optional names of the state components, used in error messages.
  std::vector<std::string> state_names;
  /// Optional: called on every accepted state to put it back on a manifold
  /// (closed loops); false, with the reason, stops the run (kRhsFailed).
  /// Output between steps comes from the unprojected dense output.
  std::function<bool(double t, double* x, std::string* why)> project;
  /// Optional: called after every accepted step with its end time and the
  /// steps accepted so far (simulate's progress line). Every integrator calls it.
  std::function<void(double t, long accepted)> on_step;
};

struct StepStats {
  long accepted = 0;
  long rejected = 0;  ///< steps rejected by the error test
  long rhs_evals = 0;
  // The implicit methods only (0 for the explicit ones).
  long newton_iterations = 0;     ///< Newton iterations (linear solves)
  long newton_failures = 0;       ///< steps retried because Newton did not converge
  long jacobian_evaluations = 0;  ///< Jacobian evaluations
  long factorizations = 0;        ///< LU factorizations of the iteration matrix
  long projections = 0;           ///< calls of opt.project
};

enum class Status {
  kSuccess,
  kStoppedByObserver,  ///< the observer returned false
  kRhsFailed,          ///< the right-hand side returned false
  kNonFinite,          ///< a derivative or the state became NaN or infinite
  kStepSizeTooSmall,   ///< the tolerance cannot be met with a representable step
  kSolverFailed,       ///< the implicit method's Newton iteration or linear solver failed repeatedly
  kMaxSteps,           ///< max_steps attempted before reaching t_end
  kInvalidArgument,    ///< bad options or initial state
};

struct IntegrationResult {
  Status status = Status::kSuccess;
  std::string message;  ///< empty on success; else says what, at which time and state
  double t = 0.0;       ///< time of the state left in x
  StepStats stats;
  bool ok() const { return status == Status::kSuccess || status == Status::kStoppedByObserver; }
};

}  // namespace kanegen::runtime
