// SPDX-License-Identifier: GPL-2.0-or-later
// Linearisation of the compiled equations M(q) u_dot = f(t, q, u) about one
// state, by central differences (Richardson-extrapolated from two steps)
// through the runner's batch mode (one
// process, one JSON line per state). Some coordinates are selected; the
// others move with given accelerations (zero for a held joint, the
// prescribed one for a prescribed joint), so the selected rows read
//   M_ss u_dot_s = r(q, u),  r = f_s - M_s,o a_o,
// and, about the state, M_ss dq_s'' + C dq_s' + K dq_s = r(state) with
// K = -dr/dq_s and C = -dr/du_s. With loops, r also holds the loop forces
// C^T lambda of given multipliers lambda (held at their value), so that K
// has their geometric stiffness, and the loops' Jacobian is returned.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "runner/runner_process.hpp"

namespace kanegen::cli {

/// The state and the parameters (all of them, in the runner's order).
struct OperatingPoint {
  double t = 0.0;
  std::vector<double> q, u, p;
};

struct LinearizeOptions {
  std::vector<int> selected;                ///< coordinate (= speed) indices, ascending
  std::vector<double> other_accelerations;  ///< per speed: the given u_dot of an unselected speed
  bool velocity = false;                    ///< also C (2 n more evaluations)
  double step = 1e-6;                       ///< relative step: h_j = step * max(1, |x_j|)
  std::vector<double> loop_forces;          ///< lambda of the loops (empty: none), M u_dot = f + C^T lambda
};

struct Linearization {
  Eigen::MatrixXd mass;       ///< M_ss at the state
  Eigen::MatrixXd stiffness;  ///< K = -dr/dq_s, as computed (not symmetrised)
  Eigen::MatrixXd velocity;   ///< C = -dr/du_s (empty unless asked for)
  Eigen::VectorXd forcing;    ///< r at the state
  Eigen::MatrixXd loops;  ///< the loops' Jacobian C in the selected speeds' columns (nc x n; 0 rows: none)
};

/// Throws std::runtime_error if the runner fails or gives a non-finite value.
Linearization linearize(runner::RunnerProcess& runner, const OperatingPoint& point,
                        const LinearizeOptions& options);

}  // namespace kanegen::cli
