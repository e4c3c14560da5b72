// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose
// (docs/licensing.md).
// The runtime's registry of integrators (methods.hpp) points at every method; an FMU carries the ones it can
// run without other libraries (rk4, dopri5, radau) and these in place of the others: bdf needs SUNDIALS
// CVODE, and genalpha steps a whole run from t = 0, not a communication step.
#include <stdexcept>
#include <string>

#include "integration_run.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen::runtime::detail {

IntegrationResult integrate_cvode(Run& run, const Jacobian&, double t0, double* x) {
  run.fail(Status::kInvalidArgument, "bdf (SUNDIALS CVODE) is not part of a kanegen FMU", t0, x);
  return run.finish(t0);
}

IntegrationResult integrate_genalpha(const ModelRun&) {
  throw std::invalid_argument("genalpha is not part of a kanegen FMU");
}

std::string genalpha_check(const IntegrationOptions&) { return "genalpha is not part of a kanegen FMU"; }

}  // namespace kanegen::runtime::detail
