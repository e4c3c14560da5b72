// SPDX-License-Identifier: MIT
// The classical fourth-order Runge-Kutta method with step dt, one step per
// output interval (rk4.hpp's stepper), behind the registry's entry
// (methods.hpp).
#include "kanegen/runtime/rk4.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "integration_run.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen::runtime::detail {
namespace {

// Returns the time of the state left in x.
double rk4(Run& run, double t0, double* x) {
  const int n = run.n();
  const OutputGrid grid(t0, run.opt().dt, run.opt().t_end);
  std::vector<double> work(5 * static_cast<size_t>(std::max(n, 1)));
  std::vector<double> saved(x, x + n);
  double t = t0;
  if (!run.emit(t, x)) return t;
  // rk4_step ignores the rhs result, so remember the first failure here and
  // skip the remaining stages of that step.
  bool failed = false;
  const auto rhs = [&](double ts, const double* xs, double* xdot) {
    if (failed || !run.eval(ts, xs, xdot)) {
      failed = true;
      std::fill(xdot, xdot + n, 0.0);
    }
  };
  for (long k = 1; k <= grid.intervals(); ++k) {
    if (run.stats().accepted >= run.opt().max_steps) {
      run.fail(Status::kMaxSteps, max_steps_message(run.opt()), t, x);
      return t;
    }
    std::copy(x, x + n, saved.begin());
    const double t_next = grid.time(k);
    rk4_step(rhs, t, t_next - t, x, n, work.data());
    if (failed || !all_finite(x, n)) {
      run.fail(Status::kNonFinite,
               "state became non-finite in the step of size " + number(t_next - t) + " starting", t,
               saved.data());
      std::copy(saved.begin(), saved.end(), x);
      return t;
    }
    run.accepted(t_next);
    t = t_next;
    if (!run.project(t, x)) return t;
    if (!run.emit(t, x)) return t;
  }
  return t;
}

}  // namespace

IntegrationResult integrate_rk4(Run& run, const Jacobian&, double t0, double* x) {
  return run.finish(rk4(run, t0, x));
}

}  // namespace kanegen::runtime::detail
