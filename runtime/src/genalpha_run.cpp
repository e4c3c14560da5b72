// SPDX-License-Identifier: MIT
// The genalpha method's registry entry (methods.hpp): the GenAlpha stepper
// (genalpha.hpp) from t = 0, one step of opt.dt per output row, with the
// conventions of integrate(): the observer at every output time,
// max_steps, and failures that name the time and state. opt.project is not
// used: the method holds the loops closed itself.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "integration_run.hpp"
#include "kanegen/runtime/genalpha.hpp"
#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime::detail {
namespace {

// t_end must be a whole number of steps: the method has no dense output to
// reach a time between two steps.
bool whole_steps(const IntegrationOptions& opt, long* steps) {
  const double r = opt.t_end / opt.dt, nearest = std::round(r);
  *steps = static_cast<long>(nearest);
  return std::abs(r - nearest) <= 1e-9 * std::max(1.0, r);
}

// A fixed-step stepper's counters as the runner's.
void copy_stats(const ImplicitStats& s, StepStats* out) {
  out->accepted = s.steps;
  out->rejected = s.rejected;
  out->newton_iterations = s.newton_iterations;
  out->jacobian_evaluations = s.jacobian_evaluations;
  out->factorizations = s.factorizations;
}

}  // namespace

std::string genalpha_check(const IntegrationOptions& opt) {
  long steps = 0;
  if (whole_steps(opt, &steps)) return "";
  return "genalpha steps by --dt exactly: t_end = " + number(opt.t_end) +
         " is not a whole number of steps dt = " + number(opt.dt);
}

IntegrationResult integrate_genalpha(const ModelRun& run) {
  const IntegrationOptions& opt = run.opt;
  GenAlphaOptions options;
  options.h = opt.dt;
  options.rho_inf = run.rho_inf;
  GenAlpha stepper(run.model, options);
  long steps = 0;
  if (!whole_steps(opt, &steps)) throw std::invalid_argument(genalpha_check(opt));
  const int nq = run.model.info().nq, nu = run.model.info().nu;
  double* x = run.x;
  IntegrationResult result;
  const auto finish = [&](Status status, const std::string& message) {
    result.status = status;
    result.message = message;
    result.t = stepper.t();
    copy_stats(stepper.stats(), &result.stats);
    return result;
  };
  std::string why;
  if (!stepper.start(0.0, x, x + nq, run.tau, &why)) return finish(Status::kRhsFailed, why);
  const auto emit = [&]() {
    std::copy(stepper.q(), stepper.q() + nq, x);
    std::copy(stepper.u(), stepper.u() + nu, x + nq);
    return !run.observer || run.observer(stepper.t(), x);
  };
  if (!emit())
    return finish(Status::kStoppedByObserver, "stopped by the observer at t=" + number(stepper.t()));
  for (long k = 1; k <= steps; ++k) {
    if (k > opt.max_steps)
      return finish(Status::kMaxSteps, max_steps_message(opt) + " at t=" + number(stepper.t()));
    if (!stepper.step(run.tau, &why)) return finish(Status::kSolverFailed, why);
    if (opt.on_step) opt.on_step(stepper.t(), k);
    if (!emit())
      return finish(Status::kStoppedByObserver, "stopped by the observer at t=" + number(stepper.t()));
  }
  return finish(Status::kSuccess, "");
}

}  // namespace kanegen::runtime::detail
