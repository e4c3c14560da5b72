// SPDX-License-Identifier: MIT
// integrate(): checks the options and the state, then runs the method's
// entry from the registry (methods.hpp). It sits on top: the methods
// (rk4.cpp, dopri5.cpp, radau.cpp, cvode.cpp) never call back into it.
#include "kanegen/runtime/integrators.hpp"

#include <cmath>
#include <string>

#include "integration_run.hpp"

namespace kanegen::runtime {

namespace {

using namespace detail;

std::string check_options(const MethodSpec& method, const IntegrationOptions& o, double t0, int n) {
  const auto finite = [](double v) { return std::isfinite(v); };
  if (n < 0) return "negative state size";
  if (!finite(t0) || !finite(o.t_end) || o.t_end < t0) return "t_end must be finite and >= t0";
  if (!finite(o.dt) || o.dt <= 0) return "dt must be positive";
  if (!((o.rtol >= 0 && finite(o.rtol)) && (o.atol >= 0 && finite(o.atol)))) return "rtol, atol must be >= 0";
  if (method.takes_tolerances && o.rtol == 0 && o.atol == 0 && o.atol_per_component.empty())
    return "rtol and atol cannot both be zero";
  if (!o.atol_per_component.empty() && static_cast<int>(o.atol_per_component.size()) != n)
    return "atol_per_component must have one entry per state component";
  for (double a : o.atol_per_component) {
    if (!(a >= 0 && finite(a))) return "atol_per_component entries must be >= 0";
  }
  if (!(o.h0 >= 0) || !(o.h_min >= 0) || !(o.h_max >= 0)) return "h0, h_min, h_max must be >= 0";
  if (o.max_steps <= 0) return "max_steps must be positive";
  if (o.max_order < 1 || o.max_order > 5) return "max_order must be 1 to 5";
  if (!(o.safety > 0 && o.safety <= 1)) return "safety must be in (0, 1]";
  if (!(o.min_factor > 0 && o.min_factor <= 1) || !(o.max_factor >= 1))
    return "need 0 < min_factor <= 1 <= max_factor";
  if (!(o.pi_beta >= 0 && o.pi_beta < 0.2)) return "pi_beta must be in [0, 0.2)";
  if ((o.t_end - t0) / o.dt > 1e15) return "too many output times (t_end - t0) / dt";
  return {};
}

// Why the call cannot run (the options, a missing Jacobian, a method that
// is not an ODE method), or "".
std::string refusal(Method method, const Rhs& rhs, double t0, const double* x, int n,
                    const IntegrationOptions& opt, const Jacobian& jacobian) {
  if (static_cast<std::size_t>(method) >= kMethodCount) return "unknown method";
  const MethodSpec& spec = resolved_spec(method);
  std::string bad = check_options(spec, opt, t0, n);
  if (bad.empty() && spec.ode == nullptr)
    bad = std::string(spec.name) + " integrates a Model, not an ODE x' = f(t, x)";
  if (bad.empty() && spec.needs_jacobians && !jacobian)
    bad = "the implicit methods need the Jacobian of the right-hand side";
  if (bad.empty() && (!rhs || (n > 0 && !x))) bad = "no right-hand side or no state";
  return bad;
}

}  // namespace

IntegrationResult integrate(Method method, const Rhs& rhs, double t0, double* x, int n,
                            const IntegrationOptions& opt, const Observer& observer,
                            const Jacobian& jacobian) {
  if (std::string bad = refusal(method, rhs, t0, x, n, opt, jacobian); !bad.empty()) {
    IntegrationResult r;
    r.status = Status::kInvalidArgument;
    r.message = bad;
    r.t = t0;
    return r;
  }
  Run run(rhs, opt, n, observer);
  if (!all_finite(x, n)) {
    run.fail(Status::kNonFinite, "initial state is not finite", t0, x);
    return run.finish(t0);
  }
  return resolved_spec(method).ode(run, jacobian, t0, x);
}

}  // namespace kanegen::runtime
