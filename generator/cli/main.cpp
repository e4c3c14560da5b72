// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen: generate, simulate and evaluate Kane's equations of a model.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "animate/animate.hpp"
#include "animate/three_js.hpp"
#include "cli/modes.hpp"
#include "cli/plot.hpp"
#include "cli/preflight.hpp"
#include "codegen/emitter.hpp"
#include "fmu/fmu_export.hpp"
#include "kanegen/runtime/options.hpp"
#include "model/model_error.hpp"
#include "pipeline/pipeline.hpp"
#include "runner/generation_interrupt.hpp"
#include "runner/runner_build.hpp"
#include "verify/verify.hpp"

namespace {

using kanegen::runner::BuildOptions;

/// Instead of CLI11's PositiveNumber and NonNegativeNumber, whose message
/// prints the largest double in 309 digits.
CLI::Validator number_at_least(double lowest, bool inclusive, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        const bool ok = CLI::detail::lexical_cast(text, v) && (inclusive ? v >= lowest : v > lowest);
        return ok ? std::string() : "needs " + what + ", got '" + text + "'";
      },
      "");
}
const CLI::Validator kPositive = number_at_least(0, false, "a positive number");
const CLI::Validator kNonNegative = number_at_least(0, true, "a number >= 0");

/// The options every subcommand has.
struct RunOptions {
  std::string model;
  bool quiet = false;
  std::vector<double> gravity;
  std::string dynamics = "auto";
};

constexpr const char* kDynamicsHelp =
    "how forward_dynamics solves M u_dot = f: recursive (articulated-body recursion, O(n) operations; "
    "trees without loops or prescribed motions), composite (composite inertias and an unrolled LDL^T, "
    "O(n^3)), or auto (default: the one with fewer operations; composite where the recursion does not "
    "apply)";

void add_common(CLI::App* command, RunOptions& options) {
  command->add_option("MODEL", options.model, "model file (.json or .urdf)")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--gravity", options.gravity,
                   "URDF only: gravity vector X,Y,Z in m/s^2 (default 0,0,-9.81)")
      ->expected(3)
      ->delimiter(',');
  command->add_flag("--quiet", options.quiet, "no progress lines on stderr");
  command->add_option("--dynamics", options.dynamics, kDynamicsHelp)
      ->check(CLI::IsMember({"auto", "recursive", "composite"}));
  // Kept for unknown_arguments_message, which names the nearest option.
  command->allow_extras();
}

BuildOptions build_options(const RunOptions& options) {
  kanegen::cli::check_gravity_option(options.model, !options.gravity.empty());
  BuildOptions b;
  b.verbose = !options.quiet;
  b.dynamics = options.dynamics == "recursive"   ? kanegen::codegen::DynamicsMethod::recursive
               : options.dynamics == "composite" ? kanegen::codegen::DynamicsMethod::composite
                                                 : kanegen::codegen::DynamicsMethod::automatic;
  if (options.gravity.size() == 3)
    b.load.urdf_gravity = {options.gravity[0], options.gravity[1], options.gravity[2]};
  return b;
}

/// The options `simulate` and `eval` pass on to the runner, registered from
/// the runner's own table (kanegen/runtime/options.hpp), so that names, help
/// and defaults are the runner's. Only what the user gave is passed on; the
/// runner applies the defaults.
struct ForwardedOptions {
  std::vector<std::pair<const kanegen::runtime::OptionSpec*, CLI::Option*>> options;
  std::map<std::string, std::vector<std::string>> values;  ///< by long name
};

void add_forwarded(CLI::App* command, const char* runner_command, ForwardedOptions& f) {
  using kanegen::runtime::ValueKind;
  for (const kanegen::runtime::OptionSpec& o : *kanegen::runtime::command_options(runner_command)) {
    const std::string names = *o.short_name != '\0' ? std::string(o.short_name) + "," + o.name : o.name;
    const std::string help = kanegen::runtime::option_help(o);  // with the default, as the runner shows it
    CLI::Option* option = nullptr;
    if (o.kind == ValueKind::kFlag) {
      option = command->add_flag(names, help);
    } else {
      option = command->add_option(names, f.values[o.name], help)->type_name(o.value);
      // One value per occurrence; a repeated single option is kept for the runner's parser to refuse.
      if (!o.repeatable) option->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
      // A required one is not marked required here: CLI11 would report it
      // missing before an unknown option (--tend for --t-end); the runner's
      // parser, run by forwarded_args, refuses it instead.
    }
    f.options.emplace_back(&o, option);
  }
}

/// The runner's command line: the command, then each option given, in table
/// order. Checked here by the runner's own parser, so that a bad value is
/// refused with the runner's message (a UsageError) before the runner is built.
std::vector<std::string> forwarded_args(const char* runner_command, const ForwardedOptions& f) {
  std::vector<std::string> args{runner_command};
  for (const auto& [spec, option] : f.options) {
    if (option->count() == 0) continue;
    if (spec->kind == kanegen::runtime::ValueKind::kFlag) {
      if (option->as<bool>()) args.emplace_back(spec->name);  // not for --stats=false
      continue;
    }
    for (const std::string& value : f.values.at(spec->name)) args.insert(args.end(), {spec->name, value});
  }
  const auto* table = kanegen::runtime::command_options(runner_command);
  kanegen::runtime::parse_options(*table, args, 1, std::string("kanegen ") + runner_command);
  return args;
}

/// What can be checked before the runner is built: the --set values against
/// the model's physics and the output file.
void check_forwarded(const std::string& model, const BuildOptions& b, const ForwardedOptions& f) {
  const auto values = [&](const char* name) {
    const auto it = f.values.find(name);
    return it == f.values.end() ? std::vector<std::string>{} : it->second;
  };
  kanegen::cli::check_sets(model, b.load, values("--set"));
  for (const std::string& output : values("--output")) kanegen::cli::check_output_file(output);
}

// Each subcommand: its options (which CLI11 fills in place, so they stay
// where main declares them), a function that registers them and one that runs it.

struct GenerateCommand {
  CLI::App* command = nullptr;
  RunOptions run;
  std::string out_dir;
  bool jacobians = false;
  std::string precision = "double";
  bool controller = false;
  int split_threshold = kanegen::codegen::kDefaultSplitThreshold;
  int batch = 0;
};

constexpr const char* kControllerHelp =
    "also emit the quadratic kernels for controllers (coriolis_matrix, output_jacobian, "
    "output_jacobian_rate, "
    "linearize) and the Jacobian kernels they use; trees without prescribed motions only "
    "(docs/controllers.md)";

constexpr const char* kJacobiansHelp =
    "also emit the Jacobian kernels of implicit integration (forcing_jacobian, "
    "mass_matrix_product_jacobian, constraint_force_jacobian); they add generation and compile time";

void add_generate(CLI::App& app, GenerateCommand& c) {
  c.command =
      app.add_subcommand("generate", "write the model's C++ kernels (header, source, runner) to a directory");
  add_common(c.command, c.run);
  c.command->add_option("-o,--output", c.out_dir, "output directory (created if needed)")->required();
  c.command->add_flag("--jacobians", c.jacobians, kJacobiansHelp);
  c.command
      ->add_option("--precision", c.precision,
                   "the kernels' floating-point type: double (default), or float for an FPU with single "
                   "precision only (writes <name>_float.hpp and .cpp, no runner; every kernel, closed "
                   "loops included; not with --jacobians or --controller; docs/embedded.md)")
      ->check(CLI::IsMember({"double", "float"}));
  c.command->add_flag("--controller", c.controller, kControllerHelp);
  c.command
      ->add_option(
          "--split-threshold", c.split_threshold,
          "emit a kernel of more than N operations as functions of at most about min(N, 1000) operations, so "
          "that the compile time grows linearly with the model; 0: never split")
      ->type_name("N")
      ->capture_default_str()
      ->check(kNonNegative);
  c.command
      ->add_option(
          "--batch", c.batch,
          "also write <name>_batchW.hpp and .cpp: forward_dynamics and inverse_dynamics over W = 4 or 8 "
          "states per call (SIMD lanes by GCC/Clang vector extensions, a portable struct elsewhere; "
          "structure of arrays; double, trees without loops or prescribed motions; "
          "docs/architecture.md#batched-kernels)")
      ->type_name("W")
      ->check(CLI::IsMember({4, 8}));
}

int run_generate(const GenerateCommand& c) {
  const BuildOptions b = build_options(c.run);
  kanegen::cli::check_output_directory(c.out_dir);
  const kanegen::pipeline::GeneratedModel g = [&] {
    const kanegen::runner::StopWhileGenerating stop(c.run.model, "written");
    return kanegen::pipeline::generate(
        c.run.model, b.load,
        {c.jacobians, c.controller,
         c.precision == "float" ? kanegen::codegen::Precision::single_precision
                                : kanegen::codegen::Precision::double_precision,
         b.dynamics, c.split_threshold, c.batch});
  }();
  kanegen::codegen::write_files_atomically(c.out_dir, g.files);
  if (!c.run.quiet) {
    std::printf(
        "%s: %d coordinates, %zu intermediates; load %.3f s, derive %.3f s, choose %.3f s, emit %.3f s",
        g.name.c_str(), g.nq, g.intermediates, g.seconds.load, g.seconds.derive, g.seconds.choose,
        g.seconds.emit);
    if (c.jacobians || c.controller)
      std::printf(", emit with %s %.3f s", c.controller ? "controller kernels" : "jacobians",
                  g.seconds.jacobians);
    std::printf("\n");
    if (g.dynamics.recursive_operations < 0)
      std::printf("  forward_dynamics: composite inertias (%ld operations; the recursion does not apply)\n",
                  g.dynamics.composite_operations);
    else
      std::printf("  forward_dynamics: %s (recursive %ld operations, composite %ld)\n",
                  g.dynamics.recursive ? "recursive" : "composite inertias", g.dynamics.recursive_operations,
                  g.dynamics.composite_operations);
    for (const auto& [kernel, count] : g.operations)
      std::printf("  %-28s %8ld operations\n", kanegen::codegen::signature(kernel).name, count);
    for (const auto& [file, content] : g.files)
      std::printf("  wrote %s\n", (std::filesystem::path(c.out_dir) / file).c_str());
  }
  return 0;
}

struct SimulateCommand {
  CLI::App* command = nullptr;
  RunOptions run;
  ForwardedOptions forwarded;
  std::string plot;                          ///< --plot FIG.png
  kanegen::animate::AnimateOptions animate;  ///< --animate DIR (its output_dir) and --animate-*
};

void add_simulate(CLI::App& app, SimulateCommand& c) {
  c.command = app.add_subcommand(
      "simulate",
      "generate (cached), compile and integrate the model: the CSV on stdout (or -o FILE), every message "
      "on stderr (progress, --stats and its summary line, errors; 2>&1 to pipe them along)");
  add_common(c.command, c.run);
  add_forwarded(c.command, "simulate", c.forwarded);
  c.command
      ->add_option("--plot", c.plot,
                   "also draw the result, every column against t, into FIG.png (kanegen plot)")
      ->type_name("FIG.png");
  kanegen::animate::AnimateOptions& a = c.animate;
  a.format = "html";
  CLI::Option* animate =
      c.command->add_option("--animate", a.output_dir,
                            "also draw the run frame by frame into DIR (kanegen animate): DIR/MODEL.html, or "
                            "DIR/MODEL.pvd and its frames with --animate-format vtk");
  animate->type_name("DIR");
  c.command
      ->add_option("--animate-format", a.format,
                   "what --animate writes: html, one page for the browser, or vtk, a ParaView series")
      ->capture_default_str()
      ->check(CLI::IsMember({"vtk", "html"}))
      ->needs(animate);
  c.command->add_option("--animate-scale", a.scale, "--animate: magnification of the elastic displacements")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e12))
      ->needs(animate);
  c.command
      ->add_option("--animate-frames", a.frames, "--animate: at most this many frames, spread over the run")
      ->capture_default_str()
      ->check(CLI::Range(2, 1000000))
      ->needs(animate);
}

/// The CSV of a `simulate --plot` or `--animate` run without -o: a temporary
/// file next to the plot (or in the animation's directory), copied to stdout
/// afterwards (as without them) and removed.
std::string temporary_csv(const SimulateCommand& c) {
  const std::filesystem::path p =
      c.plot.empty() ? std::filesystem::path(c.animate.output_dir) / "run" : std::filesystem::path(c.plot);
  return ((p.has_parent_path() ? p.parent_path() : std::filesystem::path(".")) /
          ("." + p.filename().string() + ".csv.tmp." + std::to_string(getpid())))
      .string();
}

/// Writes the temporary CSV to stdout and removes it (read first: a closed
/// stdout must not leave it behind).
void pass_to_stdout(const std::string& csv) {
  std::ostringstream text;
  text << std::ifstream(csv).rdbuf();
  std::filesystem::remove(csv);
  std::cout << text.str() << std::flush;
}

/// --plot and --animate, from the run's CSV.
int draw(const SimulateCommand& c, const std::string& csv) {
  int status = 0;
  if (!c.plot.empty()) {
    kanegen::cli::PlotOptions p;
    p.csv = csv;
    p.output = c.plot;
    p.title = std::filesystem::path(c.run.model).filename().string();
    p.verbose = !c.run.quiet;
    status = kanegen::cli::plot(p);
  }
  if (status == 0 && !c.animate.output_dir.empty()) {
    kanegen::animate::AnimateOptions a = c.animate;
    a.result = csv;
    a.model = c.run.model;
    a.load = build_options(c.run).load;
    if (const auto sets = c.forwarded.values.find("--set"); sets != c.forwarded.values.end())
      a.sets = sets->second;
    a.verbose = !c.run.quiet;
    const std::string written = kanegen::animate::animate(a);
    if (a.verbose)
      std::fprintf(stderr, "kanegen: wrote %s (open it in %s)\n", written.c_str(),
                   a.format == "html" ? "a web browser" : "ParaView");
  }
  return status;
}

int simulate_and_draw(const SimulateCommand& c, const std::string& runner, std::vector<std::string> args) {
  const auto given = c.forwarded.values.find("--output");
  const bool to_file = given != c.forwarded.values.end() && !given->second.empty() &&
                       given->second[0] != "-" && !given->second[0].empty();
  const std::string csv = to_file ? given->second[0] : temporary_csv(c);
  if (!to_file) {
    args.erase(std::remove(args.begin(), args.end(), "-"), args.end());
    args.erase(std::remove(args.begin(), args.end(), "--output"), args.end());
    args.insert(args.end(), {"--output", csv});
    kanegen::cli::create_output_directory(csv);
  }
  int status = kanegen::runner::run_program(runner, args);
  if (status == 0) {
    try {
      status = draw(c, csv);
    } catch (...) {
      if (!to_file) pass_to_stdout(csv);  // the result is kept even when its plot or animation fails
      throw;
    }
  }
  if (!to_file) pass_to_stdout(csv);
  return status;
}

/// The --integrator value forwarded to the runner's simulate, or "" if none was given.
std::string forwarded_integrator(const ForwardedOptions& f) {
  for (const auto& [spec, option] : f.options)
    if (std::string(spec->name) == "--integrator" && option->count() > 0 && !f.values.at(spec->name).empty())
      return f.values.at(spec->name).back();
  return "";
}

/// The runner's own simulate, with the options passed on; the Jacobian
/// kernels are generated when the chosen integrator needs them.
int run_simulate(const SimulateCommand& c) {
  const std::vector<std::string> args = forwarded_args("simulate", c.forwarded);
  BuildOptions b = build_options(c.run);
  b.jacobians = kanegen::runner::integrator_needs_jacobians(forwarded_integrator(c.forwarded));
  check_forwarded(c.run.model, b, c.forwarded);
  if (!c.plot.empty()) {
    kanegen::cli::check_output_file(c.plot);
    kanegen::cli::gnuplot_or_throw();  // before the build and the run, not after
  }
  if (!c.animate.output_dir.empty()) {  // the same for --animate: where it writes, and (html) three.js
    kanegen::cli::check_output_directory(c.animate.output_dir);
    if (c.animate.format == "html") kanegen::animate::three_js_text();
  }
  const std::string runner = kanegen::runner::build_runner(c.run.model, b);
  if (const auto o = c.forwarded.values.find("--output"); o != c.forwarded.values.end())
    for (const std::string& output : o->second) kanegen::cli::create_output_directory(output);
  if (!c.plot.empty() || !c.animate.output_dir.empty()) return simulate_and_draw(c, runner, args);
  return kanegen::runner::run_program(runner, args);
}

struct EvalCommand {
  CLI::App* command = nullptr;
  RunOptions run;
  ForwardedOptions forwarded;
};

void add_eval(CLI::App& app, EvalCommand& c) {
  c.command = app.add_subcommand("eval", "print M, f, udot and the energies at one state, as JSON");
  add_common(c.command, c.run);
  add_forwarded(c.command, "eval", c.forwarded);
}

/// The runner's own eval, with the options passed on.
int run_eval(const EvalCommand& c) {
  const std::vector<std::string> args = forwarded_args("eval", c.forwarded);
  const BuildOptions b = build_options(c.run);
  check_forwarded(c.run.model, b, c.forwarded);
  const std::string runner = kanegen::runner::build_runner(c.run.model, b);
  return kanegen::runner::run_program(runner, args);
}

struct VerifyCommand {
  CLI::App* command = nullptr;
  RunOptions run;
  kanegen::verify::VerifyOptions options;
  bool jacobians = false;
  bool controller = false;
};

void add_verify(CLI::App& app, VerifyCommand& c) {
  CLI::App* ver = c.command = app.add_subcommand(
      "verify", "check the compiled kernels against an independent numeric derivation at random states");
  add_common(ver, c.run);
  ver->footer(
      "Compares M, f, udot, the energies, the outputs, inverse_dynamics, gravity and nonconservative_power\n"
      "of the compiled kernels with a numeric derivation (dual numbers, no computer algebra) at random\n"
      "states and parameters; checks that M is symmetric positive definite and the Hessian of T in u, and\n"
      "the power balance d(T+V)/dt = P_nc along short trajectories. --jacobians and --controller add the\n"
      "optional kernels. Exit status 0: all agree; 1: a mismatch (named on stderr with its state). See "
      "docs/verify.md.");
  kanegen::verify::VerifyOptions& o = c.options;
  ver->add_option("--samples", o.samples, "number of random states")->capture_default_str()->check(kPositive);
  ver->add_option("--seed", o.seed, "random seed")->capture_default_str();
  ver->add_option("--rtol", o.rtol, "tolerance of the relative error measures (power balance: 100x)")
      ->capture_default_str()
      ->check(kPositive);
  ver->add_option("--spread", o.spread, "parameters drawn in default*[1-S, 1+S] (0: the defaults)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.99));
  ver->add_option("--trajectories", o.trajectories, "power-balance trajectories (0: none)")
      ->capture_default_str()
      ->check(kNonNegative);
  ver->add_option("--duration", o.duration, "length of each trajectory in s")
      ->capture_default_str()
      ->check(kPositive);
  ver->add_option(
         "--kernels", o.kernels_dir,
         "verify this directory of generated files (from 'kanegen generate', possibly edited) instead of "
         "generating the kernels afresh")
      ->check(CLI::ExistingDirectory);
  ver->add_flag("--json", o.json, "print the report as JSON on stdout");
  ver->add_flag("--jacobians", c.jacobians,
                "generate the Jacobian kernels too and check them against central differences of the numeric "
                "path (with --kernels: checked when the files have them)");
  ver->add_flag(
      "--controller", c.controller,
      "generate the controller kernels too (coriolis_matrix, output_jacobian, output_jacobian_rate, "
      "linearize) and check them against the numeric path (with --kernels: checked when the files "
      "have them; not applicable to loops and prescribed motions)");
}

// verify and modes compute in kanegen itself, with the runner as a
// coprocess, and write nothing until their verdict: stopped by the user they
// end at once with the message and status of an interrupted simulation (the
// runner sees its input close and ends too). While a runner is compiled,
// run_program's own handler reports the interruption instead.
char g_interrupted_message[3][160];

extern "C" void stop_now(int signal_number) {
  const int k = signal_number == SIGINT ? 0 : signal_number == SIGTERM ? 1 : 2;
  const char* message = g_interrupted_message[k];
  if (write(STDERR_FILENO, message, std::strlen(message)) < 0) {
  }
  _exit(128 + signal_number);
}

void stop_on_signal(const char* command) {
  const int signals[3] = {SIGINT, SIGTERM, SIGHUP};
  const char* names[3] = {"SIGINT", "SIGTERM", "SIGHUP"};
  for (int k = 0; k < 3; ++k) {
    std::snprintf(g_interrupted_message[k], sizeof g_interrupted_message[k],
                  "error: interrupted by %s; kanegen %s stopped before its result\n", names[k], command);
    std::signal(signals[k], stop_now);
  }
}

int run_verify(VerifyCommand& c) {
  stop_on_signal("verify");
  c.options.model = c.run.model;
  c.options.build = build_options(c.run);
  // With --kernels nothing is generated, so --dynamics would be ignored:
  // the files' forward_dynamics is the one they were generated with.
  if (!c.options.kernels_dir.empty() && c.command->get_option("--dynamics")->count() > 0)
    throw kanegen::runtime::UsageError("--dynamics has no effect with --kernels: the kernels in " +
                                       c.options.kernels_dir +
                                       " were generated already; regenerate them with 'kanegen generate "
                                       "--dynamics " +
                                       c.run.dynamics + "' or leave --dynamics out");
  c.options.build.jacobians = c.jacobians;
  c.options.build.controller = c.controller;
  return kanegen::verify::verify(c.options);
}

struct ModesCommand {
  CLI::App* command = nullptr;
  RunOptions run;
  kanegen::cli::ModesOptions options;
};

void add_modes(CLI::App& app, ModesCommand& c) {
  CLI::App* modes = c.command = app.add_subcommand(
      "modes", "natural frequencies and mode shapes of the model linearised about its initial state (JSON)");
  add_common(modes, c.run);
  modes->footer(
      "Linearises the compiled equations about the initial state (q0, u0 of the model, or --q0/--u0; t = 0)\n"
      "by central differences and solves K phi = omega^2 M phi with the symmetric part of K. The\n"
      "eigen-coordinates are the elastic coordinates of the flexible bodies; free joints are held at\n"
      "their initial state (with --free-joints, or in a model without flexible bodies, their coordinates\n"
      "join in); prescribed joints move as prescribed, so a hub spinning at a constant rate gives the\n"
      "rotating-beam frequencies. With loops, the motions that keep them closed (C dq = 0), with the\n"
      "stiffness of the loop forces at the state. Mode shapes are mass-normalised, largest entry\n"
      "positive. Exit status 1\n"
      "if a mode is unstable (omega^2 < 0; the JSON marks it \"stable\": false). See docs/modes.md.");
  kanegen::cli::ModesOptions& o = c.options;
  modes->add_option("--set", o.sets, "parameter value NAME=VALUE (repeatable)");
  modes->add_option("--q0", o.q0, "operating point: initial coordinate NAME=VALUE (repeatable)");
  modes->add_option("--u0", o.u0, "initial speed NAME=VALUE (repeatable)");
  modes->add_flag("--free-joints", o.free_joints,
                  "include the free (not prescribed) joint coordinates in the eigenproblem");
  modes->add_option("--count", o.count, "print only the K lowest modes (default: all)")
      ->type_name("K")
      ->check(CLI::Range(1, 1000000));
  modes->add_flag("--matrices", o.matrices,
                  "also print M, K = -dr/dq, C = -dr/du and r at the initial state");
  modes->add_option("--step", o.step, "relative finite-difference step")
      ->capture_default_str()
      ->check(CLI::Range(1e-10, 1e-2));
}

int run_modes(ModesCommand& c) {
  stop_on_signal("modes");
  c.options.model = c.run.model;
  c.options.build = build_options(c.run);
  kanegen::cli::check_sets(c.run.model, c.options.build.load, c.options.sets, false);
  return kanegen::cli::modes(c.options);
}

struct PlotCommand {
  CLI::App* command = nullptr;
  kanegen::cli::PlotOptions options;
  bool quiet = false;
};

void add_plot(CLI::App& app, PlotCommand& c) {
  c.command = app.add_subcommand("plot", "draw columns of a result CSV against t into a PNG (with gnuplot)");
  kanegen::cli::PlotOptions& o = c.options;
  c.command->add_option("RESULT", o.csv, "a CSV written by kanegen simulate")
      ->required()
      ->check(CLI::ExistingFile);
  c.command->add_option("--y", o.columns, "a column to draw (repeatable; default: all but t, at most 12)")
      ->type_name("COL");
  c.command->add_option("-o,--output", o.output, "the PNG to write (default: RESULT with .png)")
      ->type_name("FIG.png");
  c.command->add_option("--width", o.width, "width in pixels")
      ->capture_default_str()
      ->check(CLI::Range(100, 10000));
  c.command->add_option("--height", o.height, "height in pixels")
      ->capture_default_str()
      ->check(CLI::Range(100, 10000));
  c.command->add_flag("--quiet", c.quiet, "no progress lines on stderr");
  c.command->allow_extras();
}

int run_plot(PlotCommand& c) {
  c.options.verbose = !c.quiet;
  return kanegen::cli::plot(c.options);
}

struct AnimateCommand {
  CLI::App* command = nullptr;
  kanegen::animate::AnimateOptions options;
  bool quiet = false;
};

void add_animate(CLI::App& app, AnimateCommand& c) {
  c.command =
      app.add_subcommand("animate",
                         "draw a simulation's bodies frame by frame: a ParaView time series or a page "
                         "for the browser");
  kanegen::animate::AnimateOptions& o = c.options;
  c.command->add_option("RESULT", o.result, "a CSV written by kanegen simulate")
      ->required()
      ->check(CLI::ExistingFile);
  c.command->add_option("MODEL", o.model, "the model of the run (.json or .urdf)")
      ->required()
      ->check(CLI::ExistingFile);
  c.command
      ->add_option("-o,--output", o.output_dir, "the directory for MODEL.pvd and its frames, or MODEL.html")
      ->required()
      ->type_name("DIR");
  c.command
      ->add_option("--format", o.format,
                   "vtk: a .pvd collection of .vtu files (ParaView); html: one page with a three.js viewer")
      ->capture_default_str()
      ->check(CLI::IsMember({"vtk", "html"}));
  c.command->add_option("--scale", o.scale, "magnification of the elastic displacements drawn")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e12));
  c.command->add_option("--frames", o.frames, "at most this many frames, spread evenly over the run")
      ->capture_default_str()
      ->check(CLI::Range(2, 1000000));
  c.command->add_option("--set", o.sets, "a parameter value of the run, NAME=VALUE (repeatable)")
      ->type_name("NAME=VALUE");
  c.command->add_flag("--quiet", c.quiet, "no progress lines on stderr");
  c.command->allow_extras();
}

int run_animate(AnimateCommand& c) {
  c.options.verbose = !c.quiet;
  const std::string written = kanegen::animate::animate(c.options);
  if (c.options.verbose)
    std::fprintf(stderr, "kanegen: wrote %s (open it in %s)\n", written.c_str(),
                 c.options.format == "html" ? "a web browser" : "ParaView");
  return 0;
}

struct FmuCommand {
  CLI::App* command = nullptr;
  RunOptions run;
  kanegen::fmu::ExportOptions options;
  int fmi = 2;
  std::string kind = "both";
};

void add_fmu(CLI::App& app, FmuCommand& c) {
  c.command = app.add_subcommand(
      "fmu",
      "export the model as an FMU (FMI 2.0 or 3.0, model exchange and co-simulation): modelDescription.xml, "
      "a binary for this platform and the sources that build it (docs/fmu.md)");
  add_common(c.command, c.run);
  kanegen::fmu::ExportOptions& o = c.options;
  c.command->add_option("-o,--output", o.output, "the FMU to write, NAME.fmu (written whole or not at all)")
      ->required()
      ->type_name("FILE.fmu");
  c.command->add_option("--fmi", c.fmi, "the FMI version, 2 or 3")
      ->capture_default_str()
      ->check(CLI::IsMember({2, 3}));
  c.command
      ->add_option("--kind", c.kind,
                   "me (model exchange), cs (co-simulation) or both (default: one FMU with both interfaces)")
      ->check(CLI::IsMember({"me", "cs", "both"}));
  c.command
      ->add_option("--integrator", o.integrator,
                   "co-simulation: the runtime's integrator between communication points, dopri5, rk4 or "
                   "radau (implicit)")
      ->capture_default_str();
  c.command->add_option("--rtol", o.rtol, "co-simulation: dopri5's and radau's relative tolerance")
      ->capture_default_str()
      ->check(kPositive);
  c.command->add_option("--atol", o.atol, "co-simulation: their absolute tolerance")
      ->capture_default_str()
      ->check(kPositive);
  c.command->add_option("--max-step", o.max_step, "co-simulation: rk4's largest step in a communication step")
      ->capture_default_str()
      ->check(kPositive);
}

int run_fmu(FmuCommand& c) {
  kanegen::fmu::ExportOptions& o = c.options;
  const BuildOptions b = build_options(c.run);
  o.model = c.run.model;
  o.load = b.load;
  o.dynamics = b.dynamics;
  o.verbose = b.verbose;
  o.fmi_version = c.fmi;
  o.model_exchange = c.kind != "cs";
  o.co_simulation = c.kind != "me";
  try {
    kanegen::fmu::check_export_options(o);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  kanegen::fmu::export_fmu(o);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kanegen " KANEGEN_VERSION
               ": equations of motion by Kane's method, generated as C++ kernels.\n"
               "Models are kanegen JSON (docs/model-format.md) or URDF files."};
  app.set_version_flag("--version", "kanegen " KANEGEN_VERSION);
  app.require_subcommand(1);
  GenerateCommand generate;
  SimulateCommand simulate;
  EvalCommand eval;
  VerifyCommand verify;
  ModesCommand modes;
  PlotCommand plot;
  AnimateCommand animate;
  FmuCommand fmu;
  add_generate(app, generate);
  add_simulate(app, simulate);
  add_eval(app, eval);
  add_verify(app, verify);
  add_modes(app, modes);
  add_plot(app, plot);
  add_animate(app, animate);
  add_fmu(app, fmu);

  CLI11_PARSE(app, argc, argv);

  for (const CLI::App* command : {generate.command, simulate.command, eval.command, verify.command,
                                  modes.command, plot.command, animate.command, fmu.command})
    if (*command)
      if (const std::string unknown = kanegen::cli::unknown_arguments_message(*command); !unknown.empty()) {
        std::fprintf(stderr, "error: %s\n", unknown.c_str());
        return 2;
      }

  try {
    if (*generate.command) return run_generate(generate);
    if (*simulate.command) return run_simulate(simulate);
    if (*eval.command) return run_eval(eval);
    if (*verify.command) return run_verify(verify);
    if (*modes.command) return run_modes(modes);
    if (*plot.command) return run_plot(plot);
    if (*animate.command) return run_animate(animate);
    if (*fmu.command) return run_fmu(fmu);
  } catch (const kanegen::runner::Interrupted& e) {  // as an interrupted simulation reports it
    std::fprintf(stderr, "error: %s\n", e.what());
    return 128 + e.signal_number;
  } catch (const kanegen::model::ModelError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const kanegen::runtime::UsageError& e) {  // a forwarded option, as the runner would say it
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
