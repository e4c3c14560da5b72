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
  /// Writes the lines and reads their answers, one each: a thread writes
  /// while this one reads, so neither side blocks on a full pipe and the
  /// lines cost no round trip each. Throws std::runtime_error if the runner has gone.
  std::vector<std::string> exchange_all(const std::vector<std::string>& lines);
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
/// `batch` requests, their answers in order (RunnerProcess::exchange_all);
/// throws std::runtime_error if an answer is an error.
std::vector<nlohmann::json> batch_requests(RunnerProcess& process,
                                           const std::vector<nlohmann::json>& requests);

/// The kernels named (kernels.def) called by one `batch` line at the
/// state of `request` (t, q, u, tau, p and any "input_<argument>"): its
/// answer's "kernels", per kernel its outputs by argument name (a matrix
/// as its rows) and "returns" (docs/runtime.md#batch).
nlohmann::json call_kernels(RunnerProcess& process, nlohmann::json request,
                            const std::vector<std::string>& kernels);

}  // namespace kanegen::runner
