// SPDX-License-Identifier: MIT
// The power that changes T + V (private to the runtime): the generated
// nonconservative_power (dampers, inputs, efforts, body-fixed forces) plus
// the power of the drivers of prescribed motions, for the
// nonconservative_work column of --energies.
#pragma once

#include <vector>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

class NonconservativePower {
 public:
  explicit NonconservativePower(const Model& model);
  /// dW_nc/dt at (t, q, u) with the accelerations udot and loop forces
  /// lambda (nc; ignored for an open tree) that the dynamics gave there.
  /// The drivers' effort is M udot - f - C^T lambda, zero in every row but
  /// a prescribed one: its product with u is their power.
  double operator()(double t, const double* q, const double* u, const double* tau, const double* udot,
                    const double* lambda);

 private:
  const Model& model_;
  std::vector<double> M_, f_, C_;  // sized once: no allocation per call
};

}  // namespace kanegen::runtime
