// SPDX-License-Identifier: MIT
// ODE integrators for x' = f(t, x): fixed-step classical RK4, adaptive
// Dormand-Prince 5(4) with dense output, and the adaptive implicit Radau IIA
// and BDF (SUNDIALS CVODE) for stiff systems, with the Jacobian supplied,
// behind one driver, integrate(), which dispatches through the registry of
// methods (methods.hpp). The fixed-step generalized-alpha method integrates
// a Model directly (genalpha.hpp).
//
// The allocation-free RK4 steppers are in rk4.hpp (included here), which
// needs nothing else, for embedded targets.
#pragma once

#include "kanegen/runtime/integration_types.hpp"
#include "kanegen/runtime/methods.hpp"
#include "kanegen/runtime/rk4.hpp"

namespace kanegen::runtime {

/// Integrates x' = rhs(t, x) from t0 to opt.t_end, calling `observer` (if
/// set) at the output times t0, t0 + dt, t0 + 2 dt, ..., t_end; the last
/// interval may be shorter. DOPRI5 and the implicit methods step freely and
/// reach interior output times by dense output. The implicit methods (kRadau:
/// Radau IIA of order 5, simplified Newton with the LU factors of its real
/// and complex iteration matrices; kBdf: CVODE's variable-order BDF, Newton
/// with a dense LU of I - gamma J; kImplicit: the better of the two,
/// implicit_method()) need `jacobian`; a method that steps a Model, not an
/// ODE (Method::kGenAlpha), is kInvalidArgument.
/// On return x holds the state at result.t: t_end on success, else the last
/// accepted state. Never throws for numerical failures; they come back in
/// the result.
IntegrationResult integrate(Method method, const Rhs& rhs, double t0, double* x, int n,
                            const IntegrationOptions& opt, const Observer& observer,
                            const Jacobian& jacobian = {});

}  // namespace kanegen::runtime
