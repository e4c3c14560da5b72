// SPDX-License-Identifier: MIT
// The run both builds make and the line both print, so that the test can
// compare the host's and the Cortex-M4's numbers.
#pragma once

#include <stdio.h>

#include "arm7_tracking.hpp"

namespace arm7_tracking {

constexpr int kSteps = 2000;    ///< 2 s
constexpr float kStep = 1e-3f;  ///< 1 kHz control and plant step

inline void print(const Result& r) {
  printf(
      "arm7 computed torque, %d steps of %g s: tracking error max %.6e rad, final rms %.6e rad, failed steps "
      "%d\n",
      r.steps, static_cast<double>(kStep), static_cast<double>(r.max_error),
      static_cast<double>(r.final_error), r.failed_steps);
}

}  // namespace arm7_tracking
