// SPDX-License-Identifier: MIT
// Computed-torque tracking of the 7-DOF arm in single precision, the loop
// closed on a plant simulated in the same program: the code that runs
// unchanged on the host and on a Cortex-M4F (docs/embedded.md). It needs
// nothing beyond <math.h>: no heap, no exceptions, no standard library.
#pragma once

namespace arm7_tracking {

/// What a run reports: the tracking error of the joints (rad) and the
/// step count, for the host and the firmware to print alike.
struct Result {
  float max_error = 0.0f;    ///< largest |q_ref - q| of any joint over the last half of the run
  float final_error = 0.0f;  ///< the root mean square of q_ref - q over the joints at the end
  int steps = 0;
  int failed_steps = 0;  ///< plant steps whose forward_dynamics met a singular M (none expected)
};

/// The measurement hooks: called around each controller step, so that the
/// firmware can count instructions (both may be null).
struct Hooks {
  void (*before_control)() = nullptr;
  void (*after_control)() = nullptr;
};

/// Runs `steps` control periods of h seconds: the controller computes the
/// joint torques from the measured state, the plant integrates one RK4 step
/// under them (zero-order hold).
Result run(int steps, float h, const Hooks& hooks = Hooks());

}  // namespace arm7_tracking
