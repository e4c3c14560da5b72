// SPDX-License-Identifier: GPL-2.0-or-later
// The power balance d(T + V)/dt = P_nc along a short trajectory of the
// compiled model: x = [q; u; W] is integrated with DOPRI5 at tight
// tolerances (for the duration, or 400 steps if that comes first), udot from the generated forward_dynamics
// (through the runner), W' = P_nc (dampers, inputs, body-frame forces, beam damping and geometric
// stiffness, the constraint forces of prescribed speeds) from the numeric path; at each output time
// T + V (generated) must equal T0 + V0 + W.
#pragma once

#include <vector>

#include "numeric/dynamics.hpp"
#include "numeric/instance.hpp"
#include "runner/runner_process.hpp"
#include "verify/verify_report.hpp"

namespace kanegen::verify {

struct TrajectoryStart {
  const numeric::Instance* instance = nullptr;  ///< the model at the trajectory's parameter values
  numeric::State state;                         ///< initial t, q, u; constant inputs
  std::vector<double> runner_tau, runner_p;     ///< the same inputs and parameters in the runner's order
};

/// Worst |E(t) - E(0) - W(t)| / max(T + |V| + |W|) over the output times.
/// A trajectory that cannot be integrated (singular M, step size) is an
/// error of +inf with the reason as the entry.
Worst power_balance(runner::RunnerProcess& runner, const TrajectoryStart& start, double duration, int index,
                    long* points);

}  // namespace kanegen::verify
