// SPDX-License-Identifier: GPL-2.0-or-later
// Ctrl-C while a model is generated. Generation is one long computation in
// kanegen itself that cannot stop to look at a flag, and it writes nothing
// until it returns, so a signal then ends kanegen at once with the message
// and status of an interrupted simulation.
#pragma once

#include <string>

namespace kanegen::runner {

/// While alive, SIGINT, SIGTERM and SIGHUP end kanegen with
/// "error: interrupted by SIGINT while generating MODEL; nothing was WHAT"
/// on stderr and exit status 128 + signal; the previous handlers return
/// when it ends. `what`: "written" (generate -o) or "cached" (a runner build).
class StopWhileGenerating {
 public:
  StopWhileGenerating(const std::string& model, const char* what);
  ~StopWhileGenerating();
  StopWhileGenerating(const StopWhileGenerating&) = delete;
  StopWhileGenerating& operator=(const StopWhileGenerating&) = delete;

 private:
  void (*previous_[3])(int) = {};
};

}  // namespace kanegen::runner
