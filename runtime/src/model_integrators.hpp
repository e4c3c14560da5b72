// SPDX-License-Identifier: MIT
// Runs a registry method (methods.hpp) on the runner's model: a method that
// steps the Model itself through its own entry, an ODE method on the
// model's right-hand side with integrate(), the implicit ones with the
// model's exact Jacobian (StateJacobian). Private to the runtime library
// (driver.cpp); it sits on top of the registry with integrate().
#pragma once

#include "kanegen/runtime/integrators.hpp"
#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime::detail {

/// Integrates run.model with `method` from t = 0. An implicit ODE method
/// integrates the nq + nu components of x (run.n is for the explicit ones).
/// Throws std::invalid_argument for a model without the Jacobian kernels
/// the method needs, or options it cannot take.
IntegrationResult integrate_model(Method method, const ModelRun& run);

}  // namespace kanegen::runtime::detail
