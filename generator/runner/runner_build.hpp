// SPDX-License-Identifier: GPL-2.0-or-later
// Turns a model file into a compiled runner executable (the model's kernels
// linked with the runtime driver), cached by a digest of everything that
// goes into it, so repeated `simulate` and `eval` calls skip generation.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "codegen/model_kernels.hpp"
#include "model/load.hpp"

namespace kanegen::runner {

struct BuildOptions {
  bool verbose = true;  ///< progress lines on stderr
  model::LoadOptions load;
  /// The Jacobian kernels too (pipeline::GenerateOptions::jacobians); part of the cache key.
  bool jacobians = false;
  /// The controller kernels too (pipeline::GenerateOptions::controller); part of the cache key.
  bool controller = false;
  /// forward_dynamics's method (pipeline::GenerateOptions::dynamics); part of the cache key.
  codegen::DynamicsMethod dynamics = codegen::DynamicsMethod::automatic;
};

/// Whether the runner's `simulate --integrator VALUE` needs the Jacobian
/// kernels: those of the runtime's registry (methods.hpp) marked so, the
/// implicit ones.
bool integrator_needs_jacobians(const std::string& integrator);

/// The user stopped a build (SIGINT, SIGTERM or SIGHUP while compiling):
/// reported as such, with exit status 128 + signal, not as a compiler error.
struct Interrupted : std::runtime_error {
  Interrupted(const std::string& what, int signal_number)
      : std::runtime_error(what), signal_number(signal_number) {}
  int signal_number;
};

/// Returns the path of the runner for `model_path`, generating and compiling
/// it if the cache has none. Throws model::ModelError or std::runtime_error.
std::string build_runner(const std::string& model_path, const BuildOptions& options);

/// Returns the path of a shared library of `model_path`'s kernels (cached
/// like runners, in an entry of its own), generating and compiling it if the
/// cache has none. It exports
///   extern "C" int kanegen_model_table(kanegen::runtime::ModelTable* out, size_t size_of_table)
/// which fills *out with the model's kernel table and returns 0, or returns
/// nonzero when size_of_table is not sizeof(ModelTable) (a caller built
/// against another runtime). Throws model::ModelError or std::runtime_error.
std::string build_model_library(const std::string& model_path, const BuildOptions& options);

/// For the generator linked into a library rather than the kanegen
/// executable (the Python module): the path of that library, whose bytes key
/// the cache (a rebuilt generator may emit other code) and next to whose
/// install prefix the runtime headers and library are looked for (else the
/// build tree's). Default: the running executable (/proc/self/exe).
void set_generator_location(const std::string& generator_file);

/// Returns the path of a runner compiled from an existing directory of
/// generated files (<name>.hpp, <name>.cpp, <name>_runner.cpp, as written by
/// `kanegen generate`, possibly edited), cached by a digest of their content.
std::string build_runner_from_directory(const std::string& kernels_dir, const BuildOptions& options);

/// The compiler the runners are built with: $KANEGEN_CXX, else $CXX, else c++.
std::string compiler_command();

/// Runs the compiler the runners are built with ($KANEGEN_CXX, else $CXX, else c++) on `args` with
/// "-o" a temporary name next to `output`, renamed to `output` when it succeeds (kanegen fmu's binary).
/// Throws Interrupted if the user stopped it, else std::runtime_error naming `failed_file`, then
/// `if_failed` and the compiler's first messages.
void compile_with(const std::vector<std::string>& args, const std::string& output, const std::string& name,
                  const std::string& failed_file, const std::string& if_failed);

/// Runs a program with arguments, waits, and returns its exit status; its
/// stderr goes to `error_file` (created 0600, truncated) if one is given.
int run_program(const std::string& program, const std::vector<std::string>& args,
                const std::string& error_file = "");

}  // namespace kanegen::runner
