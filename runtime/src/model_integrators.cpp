// SPDX-License-Identifier: MIT
#include "model_integrators.hpp"

#include "kanegen/runtime/state_jacobian.hpp"

namespace kanegen::runtime::detail {

namespace {

// An implicit ODE method on x = (q, u), the Jacobian from the model's
// kernels with the inputs tau.
IntegrationResult integrate_implicit(Method method, const ModelRun& run) {
  StateJacobian jacobian(run.model);
  const Jacobian jac = [&](double t, const double* xs, double* J) {
    return jacobian.evaluate(t, xs, run.tau, J);
  };
  const int n = run.model.info().nq + run.model.info().nu;
  return integrate(method, run.rhs, 0.0, run.x, n, run.opt, run.observer, jac);
}

}  // namespace

IntegrationResult integrate_model(Method method, const ModelRun& run) {
  const MethodSpec& spec = resolved_spec(method);
  if (spec.model != nullptr) return spec.model(run);
  if (spec.needs_jacobians) return integrate_implicit(method, run);
  return integrate(method, run.rhs, 0.0, run.x, run.n, run.opt, run.observer);
}

}  // namespace kanegen::runtime::detail
