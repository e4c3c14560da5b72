// SPDX-License-Identifier: GPL-2.0-or-later
#include "runner/runner_build.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "codegen/cpp_printer.hpp"
#include "codegen/embedded_templates.hpp"
#include "codegen/emitter.hpp"
#include "kanegen/runtime/methods.hpp"
#include "pipeline/pipeline.hpp"
#include "runner/generation_interrupt.hpp"
#include "runner/runner_cache.hpp"

namespace kanegen::runner {
namespace fs = std::filesystem;
namespace {

struct RuntimeLocation {
  fs::path include_dir, library;
};

/// The runtime next to an installed kanegen (bin/../include, bin/../lib), else the build tree's.
RuntimeLocation locate_runtime() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path prefix = exe.parent_path().parent_path();
    for (const char* lib : {"lib", "lib64", "lib/x86_64-linux-gnu"}) {
      RuntimeLocation installed{prefix / "include", prefix / lib / "libkanegen_runtime.a"};
      if (fs::exists(installed.include_dir / "kanegen/runtime/driver.hpp") && fs::exists(installed.library))
        return installed;
    }
  }
  return {KANEGEN_RUNTIME_INCLUDE_DIR, KANEGEN_RUNTIME_LIBRARY};
}

std::string compiler() {
  const char* cxx = std::getenv("KANEGEN_CXX");
  if (!cxx || !*cxx) cxx = std::getenv("CXX");
  return cxx && *cxx ? cxx : "c++";
}

/// Everything that changes the runner: the model, the generation options,
/// the generator, the templates, the runtime (headers and library) and the compiler.
std::string cache_key(const std::string& model_path, const RuntimeLocation& runtime,
                      const BuildOptions& options) {
  std::string bytes = pipeline::read_file(model_path);
  for (double g : options.load.urdf_gravity) bytes += codegen::format_double(g) + ",";
  if (options.jacobians) bytes += "jacobians\n";  // absent otherwise: the keys of existing caches stay
  if (options.controller) bytes += "controller\n";
  if (options.dynamics == codegen::DynamicsMethod::recursive) bytes += "recursive\n";  // likewise
  if (options.dynamics == codegen::DynamicsMethod::composite) bytes += "composite\n";
  bytes += KANEGEN_VERSION;
  // The generator itself: a rebuilt kanegen of the same version may emit other code.
  std::error_code error;
  if (fs::exists("/proc/self/exe", error)) bytes += pipeline::read_file("/proc/self/exe");
  for (const char* text : embedded::all_templates()) bytes += text;
  bytes += compiler();
  for (const auto& entry : fs::recursive_directory_iterator(runtime.include_dir / "kanegen"))
    if (entry.is_regular_file()) bytes += pipeline::read_file(entry.path().string());
  bytes += pipeline::read_file(runtime.library.string());
  return pipeline::digest(bytes);
}

}  // namespace

bool integrator_needs_jacobians(const std::string& integrator) {
  // The runtime's registry decides; "" is the runner's default, an unknown
  // name is the runner's to report.
  const runtime::MethodSpec* method =
      integrator.empty() ? &runtime::method_spec(runtime::kDefaultMethod) : runtime::find_method(integrator);
  return method != nullptr && method->needs_jacobians;
}

namespace {

// The child run_program waits for; SIGINT, SIGTERM and SIGHUP sent to kanegen
// are passed on to it, so that a simulation stopped by the user closes its
// output and reports where it stopped, rather than being orphaned.
volatile pid_t g_child = 0;
// The last signal passed on, so that a compiler stopped by the user is told
// apart from one that failed.
volatile sig_atomic_t g_forwarded = 0;

extern "C" void forward_signal(int signal_number) {
  g_forwarded = signal_number;
  if (g_child > 0) kill(g_child, signal_number);
}

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

}  // namespace

int run_program(const std::string& program, const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start " + program);
  if (pid == 0) {
    execvp(program.c_str(), argv.data());
    std::fprintf(stderr, "error: cannot run %s\n", program.c_str());
    _exit(127);
  }
  g_child = pid;
  constexpr int kForwarded[] = {SIGINT, SIGTERM, SIGHUP};
  void (*previous[3])(int) = {};
  for (int i = 0; i < 3; ++i) previous[i] = std::signal(kForwarded[i], forward_signal);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  for (int i = 0; i < 3; ++i) std::signal(kForwarded[i], previous[i]);
  g_child = 0;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

namespace {

/// Compiles DIR/<name>.cpp and DIR/<name>_runner.cpp with the runtime into
/// `runner`, through a temporary name, so that a concurrent or interrupted
/// build never leaves a broken runner in the cache. `if_failed` follows the
/// file name in the message when the code does not compile.
void compile_runner(const fs::path& source_dir, const std::string& name, const RuntimeLocation& runtime,
                    const fs::path& runner, const std::string& if_failed) {
  const fs::path temporary = runner.parent_path() / ("runner.tmp." + std::to_string(getpid()));
  const std::vector<std::string> args{"-std=c++17",
                                      "-O2",
                                      "-I" + source_dir.string(),
                                      "-I" + runtime.include_dir.string(),
                                      (source_dir / (name + ".cpp")).string(),
                                      (source_dir / (name + "_runner.cpp")).string(),
                                      runtime.library.string(),
                                      "-o",
                                      temporary.string()};
  // The runtime's implicit integrator (CVODE, found at configure time), after
  // the static runtime library that needs it.
  const fs::path cvode = KANEGEN_SUNDIALS_CVODE_LIBRARY;
  std::vector<std::string> linked = args;
  linked.insert(linked.end(), {cvode.string(), "-Wl,-rpath," + cvode.parent_path().string()});
  g_forwarded = 0;
  const int status = run_program(compiler(), linked);
  if (const int signal_number = g_forwarded; signal_number != 0) {
    std::error_code ignored;
    fs::remove(temporary, ignored);  // the cache keeps no half-built runner; the next run compiles afresh
    throw Interrupted("interrupted by " + std::string(signal_name(signal_number)) + " while compiling " +
                          name + "; nothing was cached",
                      signal_number);
  }
  if (status != 0) throw std::runtime_error((source_dir / (name + ".cpp")).string() + ": " + if_failed);
  fs::rename(temporary, runner);
}

/// Whether the locked entry holds a runner as it was built; an entry changed
/// since (an edited source, a replaced runner) is discarded and reported, and
/// its runner never run.
bool usable_entry(const fs::path& dir) {
  std::string changed;
  switch (entry_state(dir, &changed)) {
    case EntryState::intact:
      return true;
    case EntryState::changed:
      std::fprintf(stderr, "kanegen: the cached runner in %s is not as it was built (%s); rebuilding it\n",
                   dir.c_str(), changed.c_str());
      discard_entry(dir);
      return false;
    case EntryState::missing:
      return false;
  }
  return false;
}

RuntimeLocation checked_runtime() {
  const RuntimeLocation runtime = locate_runtime();
  if (!fs::exists(runtime.library))
    throw std::runtime_error(runtime.library.string() +
                             ": the kanegen runtime library is missing; build or install kanegen");
  return runtime;
}

}  // namespace

std::string build_runner(const std::string& model_path, const BuildOptions& options) {
  const RuntimeLocation runtime = checked_runtime();
  const fs::path dir = checked_cache_root() / cache_key(model_path, runtime, options);
  const fs::path runner = dir / "runner";
  const EntryLock lock(dir, options.verbose);  // one builder per entry; the others wait and use its runner
  if (usable_entry(dir)) return runner.string();

  const auto start = std::chrono::steady_clock::now();
  if (options.verbose) std::fprintf(stderr, "kanegen: generating %s ...\n", model_path.c_str());
  const pipeline::GeneratedModel generated = [&] {
    const StopWhileGenerating stop(model_path, "cached");
    pipeline::GenerateOptions generate;
    generate.jacobians = options.jacobians;
    generate.controller = options.controller;
    generate.dynamics = options.dynamics;
    return pipeline::generate(model_path, options.load, generate);
  }();
  codegen::write_files_atomically(dir.string(), generated.files);

  if (options.verbose)
    std::fprintf(stderr, "kanegen: compiling %s (%ld operations in forward_dynamics) ...\n",
                 generated.name.c_str(), generated.operations.at(codegen::Kernel::forward_dynamics));
  compile_runner(dir, generated.name, runtime, runner,
                 "the generated code did not compile (see the compiler's messages above); please report this "
                 "as a kanegen bug");
  std::vector<std::string> sources;
  for (const auto& file : generated.files) sources.push_back(file.first);
  seal_entry(dir, sources);
  if (options.verbose)
    std::fprintf(stderr, "kanegen: ready in %.1f s (cached in %s)\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 dir.c_str());
  return runner.string();
}

std::string build_runner_from_directory(const std::string& kernels_dir, const BuildOptions& options) {
  const fs::path source(kernels_dir);
  if (!fs::is_directory(source)) throw std::runtime_error(kernels_dir + ": no such directory");
  // The model name from the one <name>_runner.cpp; its files are keyed by content.
  std::string name;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(source)) {
    if (!entry.is_regular_file()) continue;
    const std::string file = entry.path().filename().string();
    const std::string suffix = "_runner.cpp";
    if (file.size() > suffix.size() &&
        file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0) {
      if (!name.empty())
        throw std::runtime_error(kernels_dir + ": more than one *_runner.cpp; keep one model per directory");
      name = file.substr(0, file.size() - suffix.size());
    }
    if (entry.path().extension() == ".cpp" || entry.path().extension() == ".hpp")
      files.push_back(entry.path());
  }
  if (name.empty())
    throw std::runtime_error(kernels_dir +
                             ": no <model>_runner.cpp; give a directory written by 'kanegen generate'");
  for (const char* ext : {".hpp", ".cpp"})
    if (!fs::exists(source / (name + ext)))
      throw std::runtime_error(kernels_dir + ": " + name + ext + " is missing next to " + name +
                               "_runner.cpp");

  const RuntimeLocation runtime = checked_runtime();
  std::sort(files.begin(), files.end());
  std::string bytes = "kernels-directory\n";
  for (const fs::path& f : files) bytes += f.filename().string() + "\n" + pipeline::read_file(f.string());
  bytes += compiler();
  for (const auto& entry : fs::recursive_directory_iterator(runtime.include_dir / "kanegen"))
    if (entry.is_regular_file()) bytes += pipeline::read_file(entry.path().string());
  bytes += pipeline::read_file(runtime.library.string());
  const fs::path dir = checked_cache_root() / ("kernels-" + pipeline::digest(bytes));
  const fs::path runner = dir / "runner";
  const EntryLock lock(dir, options.verbose);
  if (usable_entry(dir)) return runner.string();

  const auto start = std::chrono::steady_clock::now();
  if (options.verbose)
    std::fprintf(stderr, "kanegen: compiling %s from %s ...\n", name.c_str(), kernels_dir.c_str());
  compile_runner(source, name, runtime, runner,
                 "the code did not compile (see the compiler's messages above); the files in " + kernels_dir +
                     " must be as written by 'kanegen generate', and edits must compile");
  seal_entry(dir, {});  // the sources are the user's, keyed by their content
  if (options.verbose)
    std::fprintf(stderr, "kanegen: ready in %.1f s (cached in %s)\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 dir.c_str());
  return runner.string();
}

}  // namespace kanegen::runner
