// SPDX-License-Identifier: MIT
// The tracking run on the host: the same code as the firmware's, printed the same way.
#include <cstdio>

#include "arm7_tracking.hpp"
#include "report.hpp"

int main() {
  const arm7_tracking::Result r = arm7_tracking::run(arm7_tracking::kSteps, arm7_tracking::kStep);
  arm7_tracking::print(r);
  return r.failed_steps == 0 ? 0 : 1;
}
