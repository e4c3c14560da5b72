// SPDX-License-Identifier: MIT
// ODE integrators for x' = f(t, x): fixed-step classical RK4 and adaptive
// Dormand-Prince 5(4) with dense output, behind one driver, integrate().
//
// The allocation-free RK4 steppers are in rk4.hpp (included here), which
// needs nothing else, for embedded targets.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "kanegen/runtime/rk4.hpp"

namespace kanegen::runtime {

enum class Method { kRk4, kDopri5 };

/// "rk4" or "dopri5".
const char* method_name(Method method);
/// Parses "rk4" / "dopri5"; false if unknown.
bool parse_method(std::string_view text, Method* method);

/// x' = f(t, x). Returns false if f cannot be evaluated at (t, x), which
/// stops the integration with Status::kRhsFailed.
using Rhs = std::function<bool(double t, const double* x, double* xdot)>;
/// Called at each output time with the state there; false stops the run.
using Observer = std::function<bool(double t, const double* x)>;

struct IntegrationOptions {
  double t_end = 1.0;
  double dt = 0.01;                        ///< output interval; also the RK4 step
  double rtol = 1e-8;                      ///< DOPRI5: relative tolerance, all components
  double atol = 1e-10;                     ///< DOPRI5: absolute tolerance, all components
  std::vector<double> atol_per_component;  ///< DOPRI5: overrides atol if non-empty (size n)
  double h0 = 0.0;                         ///< DOPRI5 initial step; 0: estimated (Hairer's hinit)
  double h_min = 0.0;                      ///< DOPRI5: give up below this step; 0: 16 ulps of t
  double h_max = 0.0;                      ///< DOPRI5: largest step; 0: t_end - t0
  long max_steps = 10000000;               ///< attempted steps (accepted + rejected) before giving up
  double safety = 0.9;                     ///< step-size controller safety factor
  double min_factor = 0.2;                 ///< smallest step change per step
  double max_factor = 10.0;                ///< largest step change per step
  double pi_beta = 0.04;                   ///< PI controller gain (Hairer's beta); 0: plain I controller
  /// Optional names of the state components, used in error messages.
  std::vector<std::string> state_names;
  /// Optional: called on every accepted state to put it back on a manifold
  /// (closed loops); false, with the reason, stops the run (kRhsFailed).
  /// Output between steps comes from the unprojected dense output.
  std::function<bool(double t, double* x, std::string* why)> project;
};

struct StepStats {
  long accepted = 0;
  long rejected = 0;
  long rhs_evals = 0;
};

enum class Status {
  kSuccess,
  kStoppedByObserver,  ///< the observer returned false
  kRhsFailed,          ///< the right-hand side returned false
  kNonFinite,          ///< a derivative or the state became NaN or infinite
  kStepSizeTooSmall,   ///< the tolerance cannot be met with a representable step
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

/// Integrates x' = rhs(t, x) from t0 to opt.t_end, calling `observer` (if
/// set) at the output times t0, t0 + dt, t0 + 2 dt, ..., t_end; the last
/// interval may be shorter. DOPRI5 steps freely and reaches interior output
/// times by dense output. On return x holds the state at result.t: t_end on
/// success, else the last accepted state. Never throws for numerical
/// failures; they come back in the result.
IntegrationResult integrate(Method method, const Rhs& rhs, double t0, double* x, int n,
                            const IntegrationOptions& opt, const Observer& observer);

}  // namespace kanegen::runtime
