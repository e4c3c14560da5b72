// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen verify's check of the Jacobian kernels (models generated with
// --jacobians): df/dq, df/du, d(M a)/dq and d(C^T lambda)/dq of the runner
// against central differences, with one Richardson step, of the numeric
// path's f, M and C (generator/numeric). The numeric path differentiates
// its position functions with dual numbers but evaluates f, M and C in
// doubles, so their derivatives are taken by differences; the tolerance
// allows for the differences' round-off, which is estimated entry by entry
// (docs/verify.md).
#pragma once

#include <string>
#include <vector>

#include "numeric/dynamics.hpp"
#include "numeric/instance.hpp"
#include "runner/runner_process.hpp"
#include "verify/verify_report.hpp"

namespace kanegen::verify {

/// One state at which the Jacobians are compared.
struct JacobianPoint {
  const numeric::Instance* instance = nullptr;
  numeric::State state;
  std::vector<double> runner_tau, runner_p;  ///< in the runner's order
  int sample = 0;                            ///< its index among verify's samples
};

struct JacobianCheck {
  std::vector<std::string> coordinates;  ///< names, for the report
  /// Per coordinate: the size of its random values (1 for a joint; an
  /// elastic coordinate's scale of a small deformation), which sets the steps.
  std::vector<double> size;
  int joints = 0;  ///< coordinates [0, joints) are the joints'
  double tolerance = 1e-6;
  unsigned long seed = 1;  ///< for the fixed vectors a and lambda
};

/// The rows "forcing_jacobian df/dq", "forcing_jacobian df/du", "d(M a)/dq"
/// (mass_matrix_product_jacobian) and "d(C^T lambda)/dq"
/// (constraint_force_jacobian; not applicable to a tree), comparing at each point.
std::vector<Row> jacobian_rows(runner::RunnerProcess& process, const std::vector<JacobianPoint>& points,
                               const JacobianCheck& check);

/// The one row that stands for them when the kernels have no Jacobians.
Row jacobians_absent_row(bool requested);

}  // namespace kanegen::verify
