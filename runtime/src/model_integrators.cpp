// SPDX-License-Identifier: MIT
#include "model_integrators.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "integration_run.hpp"
#include "kanegen/runtime/genalpha.hpp"
#include "kanegen/runtime/state_jacobian.hpp"

namespace kanegen::runtime::detail {

IntegrationResult integrate_implicit(Method method, const Model& model, const Rhs& rhs, const double* tau,
                                     double* x, const IntegrationOptions& opt, const Observer& observer) {
  StateJacobian jacobian(model);
  const Jacobian jac = [&](double t, const double* xs, double* J) {
    return jacobian.evaluate(t, xs, tau, J);
  };
  return integrate(method, rhs, 0.0, x, model.info().nq + model.info().nu, opt, observer, jac);
}

long genalpha_steps(const IntegrationOptions& opt) {
  const double r = opt.t_end / opt.dt, steps = std::round(r);
  if (std::abs(r - steps) > 1e-9 * std::max(1.0, r))
    throw std::invalid_argument("genalpha steps by --dt exactly: t_end = " + number(opt.t_end) +
                                " is not a whole number of steps dt = " + number(opt.dt));
  return static_cast<long>(steps);
}

namespace {

// A fixed-step stepper's counters as the runner's.
void copy_stats(const ImplicitStats& s, StepStats* out) {
  out->accepted = s.steps;
  out->rejected = s.rejected;
  out->newton_iterations = s.newton_iterations;
  out->jacobian_evaluations = s.jacobian_evaluations;
  out->factorizations = s.factorizations;
}

}  // namespace

IntegrationResult integrate_genalpha(const Model& model, double rho_inf, const double* tau, double* x,
                                     const IntegrationOptions& opt, const Observer& observer) {
  GenAlphaOptions options;
  options.h = opt.dt;
  options.rho_inf = rho_inf;
  GenAlpha stepper(model, options);
  const long steps = genalpha_steps(opt);
  const int nq = model.info().nq, nu = model.info().nu;
  IntegrationResult result;
  const auto finish = [&](Status status, const std::string& message) {
    result.status = status;
    result.message = message;
    result.t = stepper.t();
    copy_stats(stepper.stats(), &result.stats);
    return result;
  };
  std::string why;
  if (!stepper.start(0.0, x, x + nq, tau, &why)) return finish(Status::kRhsFailed, why);
  const auto emit = [&]() {
    std::copy(stepper.q(), stepper.q() + nq, x);
    std::copy(stepper.u(), stepper.u() + nu, x + nq);
    return !observer || observer(stepper.t(), x);
  };
  if (!emit())
    return finish(Status::kStoppedByObserver, "stopped by the observer at t=" + number(stepper.t()));
  for (long k = 1; k <= steps; ++k) {
    if (k > opt.max_steps)
      return finish(Status::kMaxSteps, max_steps_message(opt) + " at t=" + number(stepper.t()));
    if (!stepper.step(tau, &why)) return finish(Status::kSolverFailed, why);
    if (opt.on_step) opt.on_step(stepper.t(), k);
    if (!emit())
      return finish(Status::kStoppedByObserver, "stopped by the observer at t=" + number(stepper.t()));
  }
  return finish(Status::kSuccess, "");
}

}  // namespace kanegen::runtime::detail
