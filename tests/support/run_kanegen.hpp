// SPDX-License-Identifier: GPL-2.0-or-later
// Running the kanegen command line from a test as a user would: a shell
// command with a private runner cache, stdout and stderr captured in files.
// Shared by the command-line test areas (cli, reliability, verify, modes).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace kanegen_test {

struct Result {
  int status = -1;  ///< exit status; -1 if kanegen did not exit normally
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A fresh directory under `root` for this process: ctest runs the test
/// cases of one executable in parallel processes.
inline std::filesystem::path process_scratch(const std::filesystem::path& root) {
  const std::filesystem::path dir = root / std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `exe args` (args in shell syntax) with KANEGEN_CACHE_DIR=cache; the
/// output goes through files in `scratch`.
inline Result run_kanegen(const std::string& exe, const std::string& cache,
                          const std::filesystem::path& scratch, const std::string& args) {
  const std::filesystem::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string command = "KANEGEN_CACHE_DIR='" + cache + "' '" + exe + "' " + args + " >'" +
                              out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace kanegen_test
