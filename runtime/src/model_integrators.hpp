// SPDX-License-Identifier: MIT
// The integrators that need the Model itself, not only x' = f(t, x): the
// adaptive implicit method (the ODE integrator of integrators.hpp with the
// model's exact Jacobian, StateJacobian) and the fixed-step methods that
// step the model's equations (GenAlpha), marched over the output grid with
// the conventions of integrate(): the observer at every output time,
// max_steps, and failures that name the time and state. Private to the
// runtime library (driver.cpp).
#pragma once

#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime::detail {

/// An adaptive implicit method (kImplicit, kRadau, kBdf) on x = (q, u):
/// `rhs` as for the explicit methods, the Jacobian from the model's kernels
/// with the inputs tau. Throws std::invalid_argument if the model has no
/// Jacobian kernels.
IntegrationResult integrate_implicit(Method method, const Model& model, const Rhs& rhs, const double* tau,
                                     double* x, const IntegrationOptions& opt, const Observer& observer);

/// The number of genalpha steps of opt.dt to opt.t_end; throws
/// std::invalid_argument if it is not whole.
long genalpha_steps(const IntegrationOptions& opt);

/// Method::kGenAlpha from t = 0: one step of opt.dt per output row (t_end
/// must be a whole number of steps), rho_inf its spectral radius at
/// infinity. opt.project is not used: the method holds the loops closed
/// itself. Throws std::invalid_argument for bad options or a model without
/// Jacobian kernels.
IntegrationResult integrate_genalpha(const Model& model, double rho_inf, const double* tau, double* x,
                                     const IntegrationOptions& opt, const Observer& observer);

}  // namespace kanegen::runtime::detail
