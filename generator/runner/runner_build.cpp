// SPDX-License-Identifier: GPL-2.0-or-later
#include "runner/runner_build.hpp"

#include <fcntl.h>
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

/// The file whose bytes identify the generator in cache keys, and next to
/// which an installed runtime is looked for: kanegen itself, unless a library
/// holding the generator said where it is (set_generator_location).
std::string& generator_file() {
  static std::string file = "/proc/self/exe";
  return file;
}

/// The runtime of an installed kanegen (PREFIX/include, PREFIX/lib), PREFIX
/// the nearest ancestor of the generator's file above its own directory that
/// has both (bin/.. for kanegen, lib/python3.X/dist-packages/.. for the
/// Python module), else the build tree's.
RuntimeLocation locate_runtime() {
  std::error_code error;
  const fs::path file = fs::canonical(generator_file(), error);
  if (!error) {
    for (fs::path prefix = file.parent_path().parent_path(); !prefix.empty(); prefix = prefix.parent_path()) {
      for (const char* lib : {"lib", "lib64", "lib/x86_64-linux-gnu"}) {
        RuntimeLocation installed{prefix / "include", prefix / lib / "libkanegen_runtime.a"};
        if (fs::exists(installed.include_dir / "kanegen/runtime/driver.hpp") && fs::exists(installed.library))
          return installed;
      }
      if (prefix == prefix.root_path()) break;
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
  if (fs::exists(generator_file(), error)) bytes += pipeline::read_file(generator_file());
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

int run_program(const std::string& program, const std::vector<std::string>& args,
                const std::string& error_file) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start " + program);
  if (pid == 0) {
    if (!error_file.empty()) {
      const int fd = open(error_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
      if (fd >= 0) dup2(fd, STDERR_FILENO);  // dup2's copy is not close-on-exec
    }
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

/// Runs the compiler with `args` and "-o" a temporary name next to `output`,
/// then renames it to `output`, so that a concurrent or interrupted build
/// never leaves a broken file in the cache. `failed_file` and `if_failed`
/// make the message when the code does not compile. With a `log`, the
/// compiler's messages go there rather than to stderr, and end the message
/// (for a caller whose stderr the user may not see, as in a notebook).
void compile_to(std::vector<std::string> args, const fs::path& output, const std::string& name,
                const fs::path& failed_file, const std::string& if_failed, const fs::path& log = {}) {
  const fs::path temporary =
      output.parent_path() / (output.filename().string() + ".tmp." + std::to_string(getpid()));
  args.insert(args.end(), {"-o", temporary.string()});
  g_forwarded = 0;
  const int status = run_program(compiler(), args, log.string());
  if (const int signal_number = g_forwarded; signal_number != 0) {
    std::error_code ignored;
    fs::remove(temporary, ignored);  // the cache keeps no half-built file; the next run compiles afresh
    throw Interrupted("interrupted by " + std::string(signal_name(signal_number)) + " while compiling " +
                          name + "; nothing was cached",
                      signal_number);
  }
  std::string said;
  if (!log.empty()) {
    std::error_code ignored;
    if (fs::exists(log, ignored)) said = pipeline::read_file(log.string());
    fs::remove(log, ignored);
    constexpr std::size_t kLimit = 8000;  // the first errors are the telling ones
    if (said.size() > kLimit) said = said.substr(0, kLimit) + "\n[...]";
  }
  if (status != 0) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error(failed_file.string() + ": " + if_failed +
                             (said.empty() ? std::string() : "; the compiler said:\n" + said));
  }
  fs::rename(temporary, output);
}

/// Compiles DIR/<name>.cpp and DIR/<name>_runner.cpp with the runtime into `runner`.
void compile_runner(const fs::path& source_dir, const std::string& name, const RuntimeLocation& runtime,
                    const fs::path& runner, const std::string& if_failed) {
  // The runtime's implicit integrator (CVODE, found at configure time), after
  // the static runtime library that needs it.
  const fs::path cvode = KANEGEN_SUNDIALS_CVODE_LIBRARY;
  compile_to({"-std=c++17", "-O2", "-I" + source_dir.string(), "-I" + runtime.include_dir.string(),
              (source_dir / (name + ".cpp")).string(), (source_dir / (name + "_runner.cpp")).string(),
              runtime.library.string(), cvode.string(), "-Wl,-rpath," + cvode.parent_path().string()},
             runner, name, source_dir / (name + ".cpp"), if_failed);
}

constexpr const char* kTableSource = "kanegen_table.cpp";

/// The model library's one export, compiled next to the generated files
/// (which stay as `kanegen generate` writes them): the model's kernel table
/// for a caller that loads the library at run time (kanegen's Python module).
/// The size argument guards against a caller built with another ModelTable.
constexpr const char* kTableExport = R"(// SPDX-License-Identifier: MIT
// This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose (docs/licensing.md).
// The entry point of a kanegen model library: the model's kernel table.
#include <cstddef>

#include <kanegen/runtime/model_table.hpp>

#include "@NAME@.hpp"

extern "C" __attribute__((visibility("default"))) int kanegen_model_table(kanegen::runtime::ModelTable* out,
                                                                          std::size_t size_of_table) {
  if (out == nullptr || size_of_table != sizeof(kanegen::runtime::ModelTable)) return 1;
  *out = kanegen_models::@NAME@::System::kernel_table<kanegen::runtime::ModelTable>();
  return 0;
}
)";

/// Writes DIR/kanegen_table.cpp and compiles it with DIR/<name>.cpp into the
/// shared library `library`.
void compile_library(const fs::path& source_dir, const std::string& name, const RuntimeLocation& runtime,
                     const fs::path& library, const std::string& if_failed) {
  std::string shim = kTableExport;
  for (std::size_t at = shim.find("@NAME@"); at != std::string::npos; at = shim.find("@NAME@", at))
    shim.replace(at, 6, name);
  codegen::write_files_atomically(source_dir.string(), {{std::string(kTableSource), shim}});
  compile_to({"-std=c++17", "-O2", "-fPIC", "-shared", "-I" + source_dir.string(),
              "-I" + runtime.include_dir.string(), (source_dir / (name + ".cpp")).string(),
              (source_dir / kTableSource).string()},
             library, name, source_dir / (name + ".cpp"), if_failed, source_dir / "compile.log");
}

/// Whether the locked entry holds its artifact (the runner, or kernels.so)
/// as it was built; an entry changed since (an edited source, a replaced
/// file) is discarded and reported, and its artifact never run.
bool usable_entry(const fs::path& dir, const std::string& artifact = "runner") {
  std::string changed;
  switch (entry_state(dir, &changed, artifact)) {
    case EntryState::intact:
      return true;
    case EntryState::changed:
      std::fprintf(stderr, "kanegen: the cached %s in %s is not as it was built (%s); rebuilding it\n",
                   artifact == "runner" ? "runner" : "model library", dir.c_str(), changed.c_str());
      discard_entry(dir, artifact);
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

/// What compile_runner and compile_library are given.
using Compile = void (*)(const fs::path& source_dir, const std::string& name, const RuntimeLocation& runtime,
                         const fs::path& output, const std::string& if_failed);

/// The cache entry's `artifact` for `model_path` (in DIR = the cache root /
/// `prefix` + the key): generated and compiled by `compile` unless the entry
/// holds it already.
std::string build_cached(const std::string& model_path, const BuildOptions& options,
                         const std::string& prefix, const std::string& artifact, Compile compile) {
  const RuntimeLocation runtime = checked_runtime();
  const fs::path dir = checked_cache_root() / (prefix + cache_key(model_path, runtime, options));
  const fs::path output = dir / artifact;
  const EntryLock lock(dir, options.verbose);  // one builder per entry; the others wait and use its output
  if (usable_entry(dir, artifact)) return output.string();

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
  // A model library's compiler messages end the message (compile_library).
  compile(dir, generated.name, runtime, output,
          artifact == "runner"
              ? "the generated code did not compile (see the compiler's messages above); please "
                "report this as a kanegen bug"
              : "the generated code did not compile; please report this as a kanegen bug");
  std::vector<std::string> sources;
  for (const auto& file : generated.files) sources.push_back(file.first);
  if (artifact != "runner") sources.push_back(kTableSource);
  seal_entry(dir, sources, artifact);
  if (options.verbose)
    std::fprintf(stderr, "kanegen: ready in %.1f s (cached in %s)\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 dir.c_str());
  return output.string();
}

}  // namespace

std::string compiler_command() { return compiler(); }

void compile_with(const std::vector<std::string>& args, const std::string& output, const std::string& name,
                  const std::string& failed_file, const std::string& if_failed) {
  const fs::path out(output);
  compile_to(args, out, name, failed_file, if_failed, out.parent_path() / (out.filename().string() + ".log"));
}

std::string build_runner(const std::string& model_path, const BuildOptions& options) {
  return build_cached(model_path, options, "", "runner", compile_runner);
}

std::string build_model_library(const std::string& model_path, const BuildOptions& options) {
  // An entry of its own ("library-" + the runner's key): its manifest seals kernels.so.
  return build_cached(model_path, options, "library-", "kernels.so", compile_library);
}

void set_generator_location(const std::string& generator_file_path) {
  generator_file() = generator_file_path;
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
