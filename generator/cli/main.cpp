// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen: generate, simulate and evaluate Kane's equations of a model.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/modes.hpp"
#include "cli/runner_build.hpp"
#include "cli/verify.hpp"
#include "codegen/emitter.hpp"
#include "model/model_error.hpp"
#include "pipeline/pipeline.hpp"

namespace {

using kanegen::cli::BuildOptions;

struct RunOptions {
  std::string model;
  std::vector<std::string> sets;
  bool quiet = false;
  std::vector<double> gravity;
};

void add_common(CLI::App* command, RunOptions& options) {
  command->add_option("MODEL", options.model, "model file (.json or .urdf)")->required()->check(CLI::ExistingFile);
  command->add_option("--gravity", options.gravity, "URDF only: gravity vector X,Y,Z in m/s^2 (default 0,0,-9.81)")
      ->expected(3)
      ->delimiter(',');
  command->add_flag("--quiet", options.quiet, "no progress lines on stderr");
}

BuildOptions build_options(const RunOptions& options) {
  BuildOptions b;
  b.verbose = !options.quiet;
  if (options.gravity.size() == 3) b.load.urdf_gravity = {options.gravity[0], options.gravity[1], options.gravity[2]};
  return b;
}

void append_pairs(std::vector<std::string>& args, const char* flag, const std::vector<std::string>& pairs) {
  for (const std::string& p : pairs) {
    args.push_back(flag);
    args.push_back(p);
  }
}

int generate(const RunOptions& options, const std::string& out_dir) {
  const BuildOptions b = build_options(options);
  const kanegen::pipeline::GeneratedModel g = kanegen::pipeline::generate(options.model, b.load);
  kanegen::codegen::write_files_atomically(out_dir, g.files);
  if (!options.quiet) {
    std::printf("%s: %d coordinates, %zu intermediates; load %.3f s, derive %.3f s, emit %.3f s\n", g.name.c_str(),
                g.nq, g.intermediates, g.seconds.load, g.seconds.derive, g.seconds.emit);
    for (const auto& [kernel, count] : g.operations)
      std::printf("  %-18s %8ld operations\n", kanegen::codegen::signature(kernel).name, count);
    for (const auto& [file, content] : g.files)
      std::printf("  wrote %s\n", (std::filesystem::path(out_dir) / file).c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kanegen " KANEGEN_VERSION
               ": equations of motion by Kane's method, generated as C++ kernels.\n"
               "Models are kanegen JSON (docs/model-format.md) or URDF files."};
  app.set_version_flag("--version", "kanegen " KANEGEN_VERSION);
  app.require_subcommand(1);

  RunOptions gen_options;
  std::string out_dir;
  CLI::App* gen = app.add_subcommand("generate", "write the model's C++ kernels (header, source, runner) to a directory");
  add_common(gen, gen_options);
  gen->add_option("-o,--output", out_dir, "output directory (created if needed)")->required();

  RunOptions sim_options;
  std::string t_end, dt = "0.01", rtol = "1e-8", atol = "1e-10";
  std::string integrator = "dopri5", csv, max_steps = "10000000";
  std::vector<std::string> q0, u0;
  bool stats = false;
  CLI::App* sim = app.add_subcommand("simulate", "generate (cached), compile and integrate the model; write CSV");
  add_common(sim, sim_options);
  sim->add_option("--t-end", t_end, "end time in s")->required()->check(CLI::Number);
  sim->add_option("--dt", dt, "output interval, and the step of rk4, in s")->capture_default_str()->check(CLI::PositiveNumber);
  sim->add_option("--integrator", integrator, "rk4 (fixed step) or dopri5 (adaptive)")->capture_default_str()
      ->check(CLI::IsMember({"rk4", "dopri5"}));
  sim->add_option("--rtol", rtol, "dopri5 relative tolerance")->capture_default_str()->check(CLI::PositiveNumber);
  sim->add_option("--atol", atol, "dopri5 absolute tolerance")->capture_default_str()->check(CLI::PositiveNumber);
  sim->add_option("--max-steps", max_steps, "fail after this many integrator steps")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  sim->add_option("--set", sim_options.sets, "parameter value NAME=VALUE (repeatable)");
  sim->add_option("--q0", q0, "initial coordinate NAME=VALUE (repeatable)");
  sim->add_option("--u0", u0, "initial speed NAME=VALUE (repeatable)");
  sim->add_option("-o,--output", csv, "CSV file (default: standard output)");
  sim->add_flag("--stats", stats, "print integrator statistics on stderr");

  RunOptions eval_options;
  std::string q_values, u_values, time = "0";
  CLI::App* eval = app.add_subcommand("eval", "print M, f, udot and the energies at one state, as JSON");
  add_common(eval, eval_options);
  eval->add_option("--q", q_values, "coordinates v1,v2,... (model order)")->required();
  eval->add_option("--u", u_values, "speeds v1,v2,... (model order)")->required();
  eval->add_option("--t", time, "time in s")->capture_default_str()->check(CLI::Number);
  eval->add_option("--set", eval_options.sets, "parameter value NAME=VALUE (repeatable)");

  RunOptions verify_options;
  kanegen::cli::VerifyOptions ver_options;
  CLI::App* ver = app.add_subcommand(
      "verify", "check the compiled kernels against an independent numeric derivation at random states");
  add_common(ver, verify_options);
  ver->footer(
      "Compares M, f, udot, the energies and the outputs of the compiled kernels with a numeric derivation\n"
      "(dual numbers, no computer algebra) at random states and parameters; checks that M is symmetric\n"
      "positive definite and the Hessian of T in u, and the power balance d(T+V)/dt = P_nc along short\n"
      "trajectories. Exit status 0: all agree; 1: a mismatch (named on stderr with its state). See "
      "docs/verify.md.");
  ver->add_option("--samples", ver_options.samples, "number of random states")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  ver->add_option("--seed", ver_options.seed, "random seed")->capture_default_str();
  ver->add_option("--rtol", ver_options.rtol,
                  "tolerance of the relative error measures (power balance: 100x)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  ver->add_option("--spread", ver_options.spread, "parameters drawn in default*[1-S, 1+S] (0: the defaults)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.99));
  ver->add_option("--trajectories", ver_options.trajectories, "power-balance trajectories (0: none)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  ver->add_option("--duration", ver_options.duration, "length of each trajectory in s")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  ver->add_option(
         "--kernels", ver_options.kernels_dir,
         "verify this directory of generated files (from 'kanegen generate', possibly edited) instead of "
         "generating the kernels afresh")
      ->check(CLI::ExistingDirectory);
  ver->add_flag("--json", ver_options.json, "print the report as JSON on stdout");

  RunOptions modes_run;
  kanegen::cli::ModesOptions modes_options;
  CLI::App* modes = app.add_subcommand(
      "modes", "natural frequencies and mode shapes of the model linearised about its initial state (JSON)");
  add_common(modes, modes_run);
  modes->footer(
      "Linearises the compiled equations about the initial state (q0, u0 of the model, or --q0/--u0; t = 0)\n"
      "by central differences and solves K phi = omega^2 M phi with the symmetric part of K. The\n"
      "eigen-coordinates are the elastic coordinates of the flexible bodies; free joints are held at\n"
      "their initial state (with --free-joints, or in a model without flexible bodies, their coordinates\n"
      "join in); prescribed joints move as prescribed, so a hub spinning at a constant rate gives the\n"
      "rotating-beam frequencies. Mode shapes are mass-normalised, largest entry positive. Exit status 1\n"
      "if a mode is unstable (omega^2 < 0; the JSON marks it \"stable\": false). See docs/modes.md.");
  modes->add_option("--set", modes_options.sets, "parameter value NAME=VALUE (repeatable)");
  modes->add_option("--q0", modes_options.q0, "operating point: initial coordinate NAME=VALUE (repeatable)");
  modes->add_option("--u0", modes_options.u0, "initial speed NAME=VALUE (repeatable)");
  modes->add_flag("--free-joints", modes_options.free_joints,
                  "include the free (not prescribed) joint coordinates in the eigenproblem");
  modes->add_option("--count", modes_options.count, "print only the K lowest modes (default: all)")
      ->type_name("K")
      ->check(CLI::Range(1, 1000000));
  modes->add_flag("--matrices", modes_options.matrices,
                  "also print M, K = -dr/dq, C = -dr/du and r at the initial state");
  modes->add_option("--step", modes_options.step, "relative finite-difference step")
      ->capture_default_str()
      ->check(CLI::Range(1e-10, 1e-2));

  CLI11_PARSE(app, argc, argv);

  try {
    if (*gen) return generate(gen_options, out_dir);
    if (*sim) {
      const std::string runner = kanegen::cli::build_runner(sim_options.model, build_options(sim_options));
      std::vector<std::string> args{"simulate", "--t-end", t_end, "--dt", dt, "--integrator", integrator,
                                    "--rtol", rtol, "--atol", atol, "--max-steps", max_steps};
      append_pairs(args, "--set", sim_options.sets);
      append_pairs(args, "--q0", q0);
      append_pairs(args, "--u0", u0);
      if (!csv.empty()) args.insert(args.end(), {"-o", csv});
      if (stats) args.push_back("--stats");
      return kanegen::cli::run_program(runner, args);
    }
    if (*eval) {
      const std::string runner = kanegen::cli::build_runner(eval_options.model, build_options(eval_options));
      std::vector<std::string> args{"eval", "--q", q_values, "--u", u_values, "--t", time};
      append_pairs(args, "--set", eval_options.sets);
      return kanegen::cli::run_program(runner, args);
    }
    if (*ver) {
      ver_options.model = verify_options.model;
      ver_options.build = build_options(verify_options);
      return kanegen::cli::verify(ver_options);
    }
    if (*modes) {
      modes_options.model = modes_run.model;
      modes_options.build = build_options(modes_run);
      return kanegen::cli::modes(modes_options);
    }
  } catch (const kanegen::model::ModelError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
