// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen verify's check of the controller kernels of `--controller`
// (coriolis_matrix, output_jacobian, output_jacobian_rate, linearize)
// against the numeric path (generator/numeric), by their defining
// properties: C u against the velocity terms of the numeric f (its part
// even in u less its value at u = 0), C + C^T against Mdot (Mdot - 2C
// skew) with Mdot by central differences of the numeric M along u, J
// against central differences of the numeric outputs in q, Jdot_u against
// their second difference along u, and linearize's A and B in the numeric
// system: M times its rows of dudot/dq, dudot/du, dudot/dtau against
// central differences of the numeric f - M a (a the numeric udot), the
// backward form, which the conditioning of M does not blur.
#pragma once

#include <string>
#include <vector>

#include "numeric/dynamics.hpp"
#include "numeric/instance.hpp"
#include "runner/runner_process.hpp"
#include "verify/verify_report.hpp"

namespace kanegen::verify {

/// One state at which the controller kernels are compared.
struct ControllerPoint {
  const numeric::Instance* instance = nullptr;
  numeric::State state;
  std::vector<double> runner_tau, runner_p;  ///< in the runner's order
  int sample = 0;                            ///< its index among verify's samples
};

struct ControllerCheck {
  std::vector<std::string> coordinates, outputs;  ///< names, for the report
  std::vector<int> input;                         ///< runner input k -> coordinate
  /// Per coordinate: the size of its random values (1 for a joint; an
  /// elastic coordinate's scale of a small deformation), which sets the steps.
  std::vector<double> size;
  int joints = 0;  ///< coordinates [0, joints) are the joints'
  double tolerance = 1e-6;
};

/// The rows "coriolis_matrix C u", "coriolis_matrix C + C^T", "output_jacobian",
/// "output_jacobian_rate", "linearize A", "linearize B", comparing at each point.
std::vector<Row> controller_rows(runner::RunnerProcess& process, const std::vector<ControllerPoint>& points,
                                 const ControllerCheck& check);

/// The same rows, not applicable for `reason` (a model with loops or
/// prescribed motions has no controller kernels).
std::vector<Row> controller_rows_not_applicable(const std::string& reason);

/// The one row that stands for them when they were not asked for.
Row controller_absent_row(bool requested);

}  // namespace kanegen::verify
