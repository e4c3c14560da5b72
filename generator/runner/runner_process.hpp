// SPDX-License-Identifier: GPL-2.0-or-later
// A model's runner kept open as a coprocess in `batch` mode (one JSON line
// in, one out), and its `info`: how kanegen verify and kanegen modes talk to
// the compiled kernels. Lockstep request/answer, so neither side can block on a full pipe.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace kanegen::runner {

class RunnerProcess {
 public:
  /// Starts `runner args...` with pipes to its stdin and stdout (stderr is
  /// inherited, so the runner's own errors reach the user).
  RunnerProcess(const std::string& runner, const std::vector<std::string>& args);
  ~RunnerProcess();
  RunnerProcess(const RunnerProcess&) = delete;
  RunnerProcess& operator=(const RunnerProcess&) = delete;

  /// Writes one line (a newline is appended) and reads the answer line.
  /// Throws std::runtime_error if the runner has gone.
  std::string exchange(const std::string& line);
  /// Reads one line of output (for commands that print without input).
  std::string read_line();
  /// Closes its input and waits; returns the exit status.
  int finish();

 private:
  std::string program_;
  pid_t pid_ = -1;
  std::FILE* to_ = nullptr;
  std::FILE* from_ = nullptr;
};

/// The runner's `info` as JSON.
nlohmann::json runner_info(const std::string& runner);

/// One `batch` request; throws std::runtime_error if the answer is an error.
nlohmann::json batch_request(RunnerProcess& process, const nlohmann::json& request);

}  // namespace kanegen::runner
