// SPDX-License-Identifier: MIT
// The main() of a compiled model ("runner"). A generated model's main is
//   int main(int c, char** v) { return kanegen::runtime::run_model<kanegen_models::NAME::System>(c, v); }
// (System::kernel_table gives the runtime its kernels: model_table.hpp).
// Subcommands: simulate, eval, info, batch (see docs/runtime.md or RUNNER --help).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

/// Runs the command line `args` (args[0] is the program name) on `model`,
/// writing results to `out` and messages to `err`. Returns the exit code:
/// 0 success, 1 failure while running, 2 bad command line. Never throws.
int run_model(Model& model, const std::vector<std::string>& args, std::FILE* out, std::FILE* err);

/// As above, with the input of the `batch` command read from `in` (the
/// overload without it reads stdin).
int run_model(Model& model, const std::vector<std::string>& args, std::FILE* in, std::FILE* out,
              std::FILE* err);

/// As above, for main(): stdin, stdout and stderr.
int run_model(Model& model, int argc, char** argv);

template <class System>
int run_model(const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  Model model = make_model<System>();
  return run_model(model, args, out, err);
}

template <class System>
int run_model(const std::vector<std::string>& args, std::FILE* in, std::FILE* out, std::FILE* err) {
  Model model = make_model<System>();
  return run_model(model, args, in, out, err);
}

template <class System>
int run_model(int argc, char** argv) {
  Model model = make_model<System>();
  return run_model(model, argc, argv);
}

}  // namespace kanegen::runtime
