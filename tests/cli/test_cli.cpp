// SPDX-License-Identifier: GPL-2.0-or-later
// The kanegen command line as a user runs it: help, generate, eval, simulate,
// and bad models. Expected values are analytic (simple pendulum). simulate
// and eval against the runner they build: the same options and defaults.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../support/run_kanegen.hpp"

namespace fs = std::filesystem;

namespace kanegen_test {
// The registry's names as the unknown-integrator message lists them (in
// test_cli_methods.cpp: the runtime's namespace kanegen would hide this
// file's function kanegen()).
std::string known_integrators();
}  // namespace kanegen_test

namespace {

using kanegen_test::known_integrators;  // test_cli_methods.cpp
using kanegen_test::Result;
using kanegen_test::slurp;

fs::path scratch() {
  static const fs::path dir = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  return dir;
}

/// Runs kanegen (arguments in shell syntax) with a private runner cache.
Result kanegen(const std::string& args) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_SCRATCH_DIR "/cache", scratch(), args);
}

std::string model(const std::string& name) { return std::string(KANEGEN_MODELS_DIR) + "/" + name; }
std::string bad(const std::string& name) { return std::string(KANEGEN_BAD_MODELS_DIR) + "/" + name; }

}  // namespace

TEST_CASE("help is available for every subcommand", "[cli]") {
  const Result top = kanegen("--help");
  CHECK(top.status == 0);
  for (const char* sub : {"generate", "simulate", "eval"}) {
    CHECK(top.out.find(sub) != std::string::npos);
    const Result r = kanegen(std::string(sub) + " --help");
    CHECK(r.status == 0);
    CHECK(r.out.find("MODEL") != std::string::npos);
  }
  CHECK(kanegen("").status != 0);
  CHECK(kanegen("frobnicate").status != 0);
}

TEST_CASE("generate writes a header, a source and a runner", "[cli]") {
  const fs::path dir = scratch() / "gen";
  const Result r = kanegen("generate " + model("double_pendulum.json") + " -o " + dir.string());
  REQUIRE(r.status == 0);
  CHECK(r.out.find("operations") != std::string::npos);
  for (const char* f : {"double_pendulum.hpp", "double_pendulum.cpp", "double_pendulum_runner.cpp"})
    CHECK(fs::exists(dir / f));
  CHECK(slurp(dir / "double_pendulum.hpp").find("struct Params") != std::string::npos);
}

TEST_CASE("generate --precision float writes float kernels, the same on every run, and no runner", "[cli]") {
  const fs::path first = scratch() / "gen_float_1", second = scratch() / "gen_float_2";
  for (const fs::path& dir : {first, second})
    REQUIRE(kanegen("generate " + model("double_pendulum.json") + " -o " + dir.string() +
                    " --quiet --precision float")
                .status == 0);
  CHECK(!fs::exists(first / "double_pendulum_float_runner.cpp"));
  for (const char* f : {"double_pendulum_float.hpp", "double_pendulum_float.cpp"}) {
    INFO(f);
    const std::string text = slurp(first / f);
    CHECK(text == slurp(second / f));
    CHECK(text.find("double ") == std::string::npos);  // "double_pendulum" is the name
    CHECK(text.find("std::") == std::string::npos);
    CHECK(text.find("namespace double_pendulum_float") != std::string::npos);
  }
  const std::string source = slurp(first / "double_pendulum_float.cpp");
  CHECK(source.find("sinf(q[0])") != std::string::npos);
  CHECK(source.find("float m1 = ") == std::string::npos);  // parameters live in the header
  CHECK(slurp(first / "double_pendulum_float.hpp").find("float m1 = 1.0f;") != std::string::npos);
  CHECK(kanegen("generate --help").out.find("--precision") != std::string::npos);
}

TEST_CASE("generate --precision float refuses Jacobians and controller kernels, and writes nothing",
          "[cli]") {
  const fs::path dir = scratch() / "gen_float_refused";
  const Result jacobians =
      kanegen("generate " + model("arm7.urdf") + " -o " + dir.string() + " --precision float --jacobians");
  CHECK(jacobians.status != 0);
  CHECK(jacobians.err.find("--precision float cannot be combined with --jacobians") != std::string::npos);
  const Result controller =
      kanegen("generate " + model("arm7.urdf") + " -o " + dir.string() + " --precision float --controller");
  CHECK(controller.status != 0);
  CHECK(controller.err.find("--precision float cannot be combined with --jacobians or --controller") !=
        std::string::npos);
  CHECK(kanegen("generate " + model("arm7.urdf") + " -o " + dir.string() + " --precision half").status != 0);
  CHECK(!fs::exists(dir / "arm7_float.cpp"));
}

// The loop kernels in float too: the saddle-point solves (the dense template
// and the unrolled sparse one) included, with float literals and sqrtf,
// nothing left in double.
TEST_CASE("generate --precision float writes the loop kernels of a model with loops in float", "[cli]") {
  const fs::path dir = scratch() / "gen_float_loops";
  REQUIRE(kanegen("generate " + model("four_bar.json") + " -o " + dir.string() + " --quiet --precision float")
              .status == 0);
  const std::string source = slurp(dir / "four_bar_float.cpp");
  CHECK(source.find("double") == std::string::npos);
  CHECK(slurp(dir / "four_bar_float.hpp").find("double") == std::string::npos);
  CHECK(source.find("int solve_saddle(float* M, float* b, float* C, const float* g, float* lambda)") !=
        std::string::npos);
  CHECK(source.find("const float l = sqrtf(s);") != std::string::npos);
  CHECK(source.find("if (!(s > 1e-06f * largest)) return -(j + 1);") != std::string::npos);
  // four_bar takes the sparse solve (fewer operations than the dense one).
  CHECK(source.find("float z[5];") != std::string::npos);
  CHECK(source.find("float s_largest = 0.0f;") != std::string::npos);
  CHECK(source.find(" > 1e-06f * s_largest)) return -") != std::string::npos);
  CHECK(source.find("void constraint_jacobian(const Params& p, const float* q, float* C)") !=
        std::string::npos);
}

TEST_CASE("generate --jacobians adds the Jacobian kernels, and only then", "[cli][jacobians]") {
  const fs::path plain = scratch() / "gen_plain", with = scratch() / "gen_jacobians";
  REQUIRE(kanegen("generate " + model("four_bar.json") + " -o " + plain.string() + " --quiet").status == 0);
  const Result r = kanegen("generate " + model("four_bar.json") + " -o " + with.string() + " --jacobians");
  REQUIRE(r.status == 0);
  for (const char* kernel :
       {"forcing_jacobian", "mass_matrix_product_jacobian", "constraint_force_jacobian"}) {
    INFO(kernel);
    CHECK(r.out.find(kernel) != std::string::npos);  // its operation count
    CHECK(slurp(with / "four_bar.hpp").find(std::string("void ") + kernel) != std::string::npos);
    CHECK(slurp(with / "four_bar.hpp").find(std::string("table.") + kernel) != std::string::npos);
    CHECK(slurp(plain / "four_bar.hpp").find(kernel) == std::string::npos);
  }
  CHECK(kanegen("generate --help").out.find("--jacobians") != std::string::npos);
  CHECK(kanegen("verify --help").out.find("--jacobians") != std::string::npos);
}

TEST_CASE(
    "generate --batch W adds the batched kernels beside unchanged files, and refuses what it cannot batch",
    "[cli][batch]") {
  const fs::path plain = scratch() / "gen_batch_plain", with = scratch() / "gen_batch";
  REQUIRE(kanegen("generate " + model("arm7.urdf") + " -o " + plain.string() + " --quiet").status == 0);
  REQUIRE(kanegen("generate " + model("arm7.urdf") + " -o " + with.string() + " --quiet --batch 8").status ==
          0);
  for (const char* f : {"arm7.hpp", "arm7.cpp", "arm7_runner.cpp"})
    CHECK(slurp(plain / f) == slurp(with / f));
  CHECK(!fs::exists(plain / "arm7_batch8.cpp"));
  const std::string header = slurp(with / "arm7_batch8.hpp"), source = slurp(with / "arm7_batch8.cpp");
  CHECK(header.find("int forward_dynamics_batch8(const Params& p, const double* t_lanes,") !=
        std::string::npos);
  CHECK(header.find("void inverse_dynamics_batch8(") != std::string::npos);
  CHECK(source.find("vector_size(8 * sizeof(double))") != std::string::npos);
  CHECK(source.find("lanes_check(status, pivot0, 1);") != std::string::npos);
  CHECK(kanegen("generate --help").out.find("--batch") != std::string::npos);
  // 4 or 8 lanes; double; open trees without prescribed motions. Nothing written.
  const fs::path refused = scratch() / "gen_batch_refused";
  CHECK(kanegen("generate " + model("arm7.urdf") + " -o " + refused.string() + " --batch 3").status != 0);
  const Result float_batch =
      kanegen("generate " + model("arm7.urdf") + " -o " + refused.string() + " --batch 4 --precision float");
  CHECK(float_batch.status != 0);
  CHECK(float_batch.err.find("--batch cannot be combined with --precision float") != std::string::npos);
  const Result loops =
      kanegen("generate " + model("four_bar.json") + " -o " + refused.string() + " --batch 4");
  CHECK(loops.status != 0);
  CHECK(loops.err.find("four_bar.json: /loops/0: the batched kernels are not made for closed loops") !=
        std::string::npos);
  CHECK(!fs::exists(refused / "arm7_batch4.cpp"));
  CHECK(!fs::exists(refused / "four_bar_batch4.cpp"));
}

TEST_CASE("eval of the simple pendulum matches the closed form", "[cli]") {
  const double q = 0.7, u = 1.3, m = 1.0, l = 1.0, g = 9.81;
  const Result r = kanegen("eval " + model("simple_pendulum.json") + " --q 0.7 --u 1.3 --quiet");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["mass_matrix"][0][0].get<double>() == Approx(m * l * l).epsilon(1e-14));
  CHECK(j["forcing"][0].get<double>() == Approx(-m * g * l * std::sin(q)).epsilon(1e-14));
  CHECK(j["udot"][0].get<double>() == Approx(-g / l * std::sin(q)).epsilon(1e-14));
  CHECK(j["kinetic_energy"].get<double>() == Approx(0.5 * m * l * l * u * u).epsilon(1e-14));
  CHECK(j["potential_energy"].get<double>() == Approx(-m * g * l * std::cos(q)).epsilon(1e-14));

  // Parameters are symbolic in the kernels: --set changes them at run time.
  const Result r2 =
      kanegen("eval " + model("simple_pendulum.json") + " --q 0.7 --u 0 --set l=2 --set m=3 --quiet");
  REQUIRE(r2.status == 0);
  const auto j2 = nlohmann::json::parse(r2.out);
  CHECK(j2["mass_matrix"][0][0].get<double>() == Approx(3.0 * 4.0).epsilon(1e-14));
  CHECK(j2["udot"][0].get<double>() == Approx(-g / 2.0 * std::sin(q)).epsilon(1e-14));
}

TEST_CASE("eval works on a URDF model and M udot = f", "[cli]") {
  const Result r =
      kanegen("eval " + model("arm7.urdf") + " --q 0.1,0.2,0.3,0.4,0.5,0.6,0.7 --u 1,-1,1,-1,1,-1,1 --quiet");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["mass_matrix"].size() == 7);
  for (int i = 0; i < 7; ++i) {
    double lhs = 0;
    for (int k = 0; k < 7; ++k) lhs += j["mass_matrix"][i][k].get<double>() * j["udot"][k].get<double>();
    CHECK(lhs == Approx(j["forcing"][i].get<double>()).margin(1e-9));
  }
}

TEST_CASE("simulate writes the CSV with the documented header", "[cli]") {
  const fs::path csv = scratch() / "pendulum.csv";
  const Result r =
      kanegen("simulate " + model("simple_pendulum.json") + " --t-end 1 --dt 0.1 --quiet -o " + csv.string());
  REQUIRE(r.status == 0);
  std::istringstream lines(slurp(csv));
  std::string header, line;
  std::getline(lines, header);
  CHECK(header == "t,pivot,pivot_dot,bob.x,bob.y,bob.z,angle");
  int rows = 0;
  double last_t = -1;
  while (std::getline(lines, line)) {
    ++rows;
    last_t = std::stod(line.substr(0, line.find(',')));
  }
  CHECK(rows == 11);
  CHECK(last_t == Approx(1.0).margin(1e-12));

  // Without -o the CSV goes to standard output; rk4 is available.
  const Result s = kanegen("simulate " + model("simple_pendulum.json") +
                           " --t-end 0.05 --dt 0.01 --integrator rk4 --quiet");
  REQUIRE(s.status == 0);
  CHECK(s.out.rfind("t,pivot,pivot_dot", 0) == 0);
}

TEST_CASE("simulate --integrator implicit and bdf and genalpha build a runner with Jacobians and CVODE",
          "[cli]") {
  // The runner links the runtime's CVODE and the model's Jacobian kernels,
  // which kanegen turns on itself; the swing follows DOPRI5's.
  const auto last_angle = [](const Result& r) {
    const std::string last = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
    return std::stod(last.substr(last.rfind(',') + 1));
  };
  const std::string run =
      "simulate " + model("simple_pendulum.json") + " --t-end 1 --dt 0.001 --quiet --stats ";
  const Result reference = kanegen(run + "--rtol 1e-12 --atol 1e-14");
  const Result implicit = kanegen(run + "--integrator implicit --rtol 1e-9 --atol 1e-11");
  const Result bdf = kanegen(run + "--integrator bdf --rtol 1e-9 --atol 1e-11");
  const Result genalpha = kanegen(run + "--integrator genalpha --rho-inf 1");
  INFO(implicit.err << bdf.err << genalpha.err);
  REQUIRE(reference.status == 0);
  REQUIRE(implicit.status == 0);
  REQUIRE(bdf.status == 0);
  REQUIRE(genalpha.status == 0);
  CHECK(implicit.err.find("stats: integrator=radau ") != std::string::npos);  // implicit is Radau
  CHECK(bdf.err.find("stats: integrator=bdf ") != std::string::npos);
  CHECK(implicit.err.find("jacobian_evals=") != std::string::npos);
  CHECK(genalpha.err.find("stats: integrator=genalpha accepted=1000 ") != std::string::npos);
  CHECK(last_angle(implicit) == Approx(last_angle(reference)).margin(1e-6));
  CHECK(last_angle(bdf) == Approx(last_angle(reference)).margin(1e-6));
  CHECK(last_angle(genalpha) == Approx(last_angle(reference)).margin(1e-4));  // second order, h = 1 ms
}

TEST_CASE("bad models end in one clear error and no output", "[cli]") {
  const fs::path dir = scratch() / "bad_out";
  fs::remove_all(dir);
  for (const char* name : {"malformed.json", "unknown_key.json", "negative_mass.json", "cycle.json",
                           "expression_unknown_name.json", "malformed.urdf", "zero_axis.urdf"}) {
    INFO(name);
    const Result r = kanegen("generate " + bad(name) + " -o " + dir.string());
    CHECK(r.status != 0);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find(name) != std::string::npos);
    CHECK(!fs::exists(dir));
  }
  const Result missing = kanegen("generate /nonexistent/model.json -o " + dir.string());
  CHECK(missing.status != 0);
  CHECK(missing.err.find("model.json") != std::string::npos);
}

TEST_CASE("a failed regeneration leaves the previous files intact", "[cli]") {
  const fs::path dir = scratch() / "keep";
  REQUIRE(kanegen("generate " + model("simple_pendulum.json") + " -o " + dir.string() + " --quiet").status ==
          0);
  const std::string before = slurp(dir / "simple_pendulum.cpp");
  // A model with the same name but an error: nothing may be written.
  const fs::path broken = scratch() / "simple_pendulum_broken.json";
  std::string text = slurp(model("simple_pendulum.json"));
  text.replace(text.find("\"mass\": \"m\""), 11, "\"mass\": \"m +\"");
  std::ofstream(broken) << text;
  CHECK(kanegen("generate " + broken.string() + " -o " + dir.string()).status != 0);
  CHECK(slurp(dir / "simple_pendulum.cpp") == before);
}

namespace {

/// kanegen with its own, fresh runner cache, which then holds one runner.
Result kanegen_fresh_cache(const fs::path& cache, const std::string& args) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, cache.string(), scratch(), args);
}

/// The runner kanegen built into `cache`.
fs::path runner_in(const fs::path& cache) {
  for (const auto& entry : fs::recursive_directory_iterator(cache))
    if (entry.path().filename() == "runner") return entry.path();
  FAIL("no runner in " << cache);
  return {};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The runner's "options:" block as (long name, help with default) pairs.
std::vector<std::pair<std::string, std::string>> runner_options(const std::string& help) {
  std::vector<std::pair<std::string, std::string>> options;
  const std::vector<std::string> lines = lines_of(help);
  auto line = std::find(lines.begin(), lines.end(), "options:");
  for (++line; line < lines.end() && line->rfind("  -", 0) == 0; ++line) {
    const size_t gap = line->find("  ", 2);
    const std::string left = line->substr(2, gap - 2);
    const size_t dashes = left.find("--");
    const std::string name = left.substr(dashes, left.find(' ', dashes) - dashes);
    if (name != "--help") options.emplace_back(name, line->substr(line->find_first_not_of(' ', gap)));
  }
  return options;
}

}  // namespace

TEST_CASE("simulate and eval show the runner's options with the runner's defaults", "[cli]") {
  const fs::path cache = scratch() / "help_cache";
  REQUIRE(kanegen_fresh_cache(cache, "eval " + model("simple_pendulum.json") + " --quiet").status == 0);
  const std::string runner = runner_in(cache).string();
  for (const char* command : {"simulate", "eval"}) {
    INFO(command);
    const Result ours = kanegen(std::string(command) + " --help");
    const Result theirs =
        kanegen_test::run_kanegen(runner, cache.string(), scratch(), std::string(command) + " --help");
    REQUIRE(ours.status == 0);
    REQUIRE(theirs.status == 0);
    const auto options = runner_options(theirs.out);
    CHECK(options.size() >= (std::string(command) == "simulate" ? 14u : 4u));
    for (const auto& [name, help] : options) {
      INFO(name << ": " << help);
      const std::vector<std::string> lines = lines_of(ours.out);
      CHECK(std::any_of(lines.begin(), lines.end(), [&, &name = name, &help = help](const std::string& l) {
        return l.find(name + " ") != std::string::npos && l.size() > help.size() &&
               l.compare(l.size() - help.size(), help.size(), help) == 0;
      }));
    }
  }
  CHECK(kanegen("simulate --help").out.find("(default 10000000)") != std::string::npos);
}

TEST_CASE("simulate and eval leave the defaults to the runner", "[cli]") {
  const fs::path cache = scratch() / "default_cache";
  const std::string pendulum = model("simple_pendulum.json");
  const Result eval =
      kanegen_fresh_cache(cache, "eval " + pendulum + " --quiet");  // q0, u0: no --q, --u needed
  REQUIRE(eval.status == 0);
  const std::string runner = runner_in(cache).string();
  const auto run_runner = [&](const std::string& args) {
    return kanegen_test::run_kanegen(runner, cache.string(), scratch(), args);
  };
  CHECK(eval.out == run_runner("eval").out);
  const Result sim = kanegen_fresh_cache(cache, "simulate " + pendulum + " --t-end 0.3 --stats --quiet");
  REQUIRE(sim.status == 0);
  const Result direct = run_runner("simulate --t-end 0.3 --stats");
  CHECK(sim.out == direct.out);
  CHECK(sim.err == direct.err);  // the same steps: the same dt, tolerances and integrator
}

TEST_CASE("simulate refuses what the runner refuses, as the runner says it, before building it", "[cli]") {
  const fs::path cache = scratch() / "refused_cache";
  const std::string pendulum = model("simple_pendulum.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--max-steps 1.5", "--max-steps needs a positive integer, got '1.5'"},
      {"--dt 0", "--dt must be positive"},
      {"--dt 0.1 --dt=0.2", "option --dt given more than once"},
      {"--integrator euler", "unknown integrator 'euler'; known: " + known_integrators()},
      {"--set m", "--set expects NAME=VALUE, got 'm'"},
  };
  for (const auto& [args, message] : cases) {
    INFO(args);
    const Result r = kanegen_fresh_cache(cache, "simulate " + pendulum + " --t-end 1 " + args);
    CHECK(r.status == 2);
    CHECK(r.err == "error: " + message + "\n");
    CHECK(!fs::exists(cache));
  }
  // The runner's rules, not stricter ones: a pure absolute tolerance is fine.
  CHECK(kanegen_fresh_cache(cache, "simulate " + pendulum + " --t-end 0.1 --rtol 0 --atol 1e-9 --quiet")
            .status == 0);
}

// ---- no silent wrong model, and mistakes found before anything is built ----

TEST_CASE("an unknown option is named, with the nearest known one", "[cli]") {
  const fs::path cache = scratch() / "unknown_option_cache";
  const Result r = kanegen_fresh_cache(cache, "simulate " + model("simple_pendulum.json") + " --tend 1");
  CHECK(r.status == 2);
  CHECK(r.err ==
        "error: unknown option --tend; did you mean --t-end? (kanegen simulate --help lists the options)\n");
  CHECK(!fs::exists(cache));
  // A required option that is missing is still reported as such.
  const Result missing = kanegen_fresh_cache(cache, "simulate " + model("simple_pendulum.json"));
  CHECK(missing.status == 2);
  CHECK(missing.err == "error: simulate needs --t-end\n");
  CHECK(
      kanegen("verify " + model("simple_pendulum.json") + " --sample 3").err ==
      "error: unknown option --sample; did you mean --samples? (kanegen verify --help lists the options)\n");
}

TEST_CASE("a JSON model refuses --gravity, before any cache entry", "[cli]") {
  const fs::path cache = scratch() / "gravity_cache";
  const Result r =
      kanegen_fresh_cache(cache, "simulate " + model("simple_pendulum.json") + " --t-end 1 --gravity 0,0,-1");
  CHECK(r.status == 2);
  CHECK(r.err ==
        "error: --gravity applies to URDF models only; " + model("simple_pendulum.json") +
            " sets gravity in its \"gravity\" field: edit it there (or write it with a parameter and use "
            "--set)\n");
  CHECK(!fs::exists(cache));
}

TEST_CASE("a bad parameter is refused at load and under --set, naming body and parameter", "[cli]") {
  const fs::path cache = scratch() / "set_cache";
  const std::string pendulum = model("simple_pendulum.json");
  const Result set = kanegen_fresh_cache(cache, "simulate " + pendulum + " --t-end 1 --set m=-1.2");
  CHECK(set.status == 2);
  CHECK(set.err ==
        "error: " + pendulum +
            ": /bodies/0/mass: negative mass (m = -1.2 from --set) of body 'pendulum'; give a positive "
            "mass in kg (check m in --set)\n");
  const Result eval = kanegen_fresh_cache(cache, "eval " + pendulum + " --set l=1 --set mm=2");
  CHECK(eval.status == 2);
  CHECK(eval.err == "error: unknown parameter 'mm' in --set; known parameters: m, l, g\n");
  CHECK(!fs::exists(cache));
  const Result modes = kanegen_fresh_cache(cache, "modes " + pendulum + " --set m=-1");
  CHECK(modes.status == 2);
  CHECK(modes.err.find("negative mass (m = -1 from --set) of body 'pendulum'") != std::string::npos);
  // The default values, at load.
  const Result load =
      kanegen("generate " + bad("negative_mass_expression.json") + " -o " + (scratch() / "never").string());
  CHECK(load.status == 2);
  CHECK(load.err ==
        "error: " + bad("negative_mass_expression.json") +
            ": /bodies/0/mass: negative mass (m1 = -1.2) of body 'a'; give a positive mass in kg (check "
            "m1 under /parameters)\n");
  CHECK(!fs::exists(scratch() / "never"));
  const Result urdf =
      kanegen("generate " + bad("misspelt_inertia_attribute.urdf") + " -o " + (scratch() / "never").string());
  CHECK(urdf.status == 2);
  CHECK(urdf.err.find(
            "line 8: <link name=\"arm\">/inertial/inertia: unknown attribute 'ixxx' of <inertia>; did "
            "you mean 'ixx'?") != std::string::npos);
}

TEST_CASE("a mass matrix singular at run time names the joint and the bodies it moves", "[cli]") {
  // Both rods massless: allowed at load (massless frames), singular at run time.
  const Result r =
      kanegen("simulate " + model("double_pendulum.json") + " --t-end 1 --quiet --set m1=0 --set m2=0 -o " +
              (scratch() / "massless.csv").string());
  CHECK(r.status == 1);
  CHECK(r.err.find(
            "error: mass matrix is not positive definite at coordinate 'shoulder' (pivot 1 of its LDL^T "
            "factorisation is not positive): joint 'shoulder' moves bodies 'link1', 'link2', one of "
            "which has a zero or negative mass or an invalid inertia at these parameters (or no mass "
            "moves along this coordinate); check their masses and inertias and the --set values; ") == 0);
}

TEST_CASE("the -o path is checked before generating and a missing directory is created", "[cli]") {
  const fs::path cache = scratch() / "output_cache";
  const std::string pendulum = model("simple_pendulum.json");
  const fs::path blocker = scratch() / "a_file";
  std::ofstream(blocker) << "not a directory\n";
  const Result r =
      kanegen_fresh_cache(cache, "simulate " + pendulum + " --t-end 1 -o " + (blocker / "out.csv").string());
  CHECK(r.status == 1);
  CHECK(r.err ==
        "error: " + blocker.string() + ": exists and is not a directory; give another output path\n");
  CHECK(!fs::exists(cache));  // nothing generated or compiled
  const Result dir =
      kanegen_fresh_cache(cache, "simulate " + pendulum + " --t-end 1 -o " + scratch().string());
  CHECK(dir.status == 1);
  CHECK(dir.err == "error: " + scratch().string() + ": is a directory; give a file name, e.g. " +
                       (scratch() / "result.csv").string() + "\n");
  CHECK(!fs::exists(cache));
  const Result gen = kanegen("generate " + pendulum + " -o " + (blocker / "gen").string());
  CHECK(gen.status == 1);
  CHECK(gen.err.find("exists and is not a directory") != std::string::npos);

  const fs::path csv = scratch() / "new" / "dir" / "pendulum.csv";
  const Result ok = kanegen("simulate " + pendulum + " --t-end 0.1 --quiet -o " + csv.string());
  CHECK(ok.status == 0);
  CHECK(slurp(csv).rfind("t,pivot,", 0) == 0);
}

TEST_CASE("Ctrl-C while compiling: interrupted, exit 130, nothing cached", "[cli]") {
  const fs::path cache = scratch() / "sigint_cache";
  const fs::path out = scratch() / "sigint_out.txt", err = scratch() / "sigint_err.txt";
  const std::string pendulum = model("double_pendulum.json");
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid ==
      0) {  // a process group of its own, as a shell gives a job: Ctrl-C reaches kanegen and the compiler
    setpgid(0, 0);
    setenv("KANEGEN_CACHE_DIR", cache.c_str(), 1);
    if (!std::freopen(out.c_str(), "w", stdout) || !std::freopen(err.c_str(), "w", stderr)) _exit(126);
    execl(KANEGEN_EXE, KANEGEN_EXE, "simulate", pendulum.c_str(), "--t-end", "1",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  // Wait until kanegen says it is compiling, then give the compiler a moment to start.
  for (int i = 0; i < 400 && slurp(err).find("compiling") == std::string::npos; ++i) usleep(25000);
  REQUIRE(slurp(err).find("compiling") != std::string::npos);
  usleep(300000);
  kill(-pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  INFO(slurp(err));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(
      slurp(err).find("error: interrupted by SIGINT while compiling double_pendulum; nothing was cached\n") !=
      std::string::npos);
  CHECK(slurp(err).find("kanegen bug") == std::string::npos);
  for (const auto& entry : fs::recursive_directory_iterator(cache)) {
    INFO(entry.path());
    CHECK(entry.path().filename() != "runner");
    CHECK(entry.path().filename().string().rfind("runner.tmp", 0) != 0);
  }
}

TEST_CASE("Ctrl-C while generating: interrupted, exit 130, nothing written or cached", "[cli]") {
  // chain20's derivation with its Jacobian kernels takes over 2 s: long
  // enough to be stopped in the middle.
  const std::string chain = model("chain20.urdf");
  const auto interrupt = [&](const std::vector<const char*>& args, const fs::path& cache, const fs::path& err,
                             useconds_t delay) {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      setpgid(0, 0);
      setenv("KANEGEN_CACHE_DIR", cache.c_str(), 1);
      if (!std::freopen(err.c_str(), "w", stderr)) _exit(126);
      std::vector<char*> argv{const_cast<char*>(KANEGEN_EXE)};
      for (const char* a : args) argv.push_back(const_cast<char*>(a));
      argv.push_back(nullptr);
      execv(KANEGEN_EXE, argv.data());
      _exit(127);
    }
    setpgid(pid, pid);
    for (int i = 0; i < 400 && slurp(err).find("generating") == std::string::npos && delay == 0; ++i)
      usleep(25000);
    usleep(delay > 0 ? delay : 500000);
    kill(-pid, SIGINT);
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    INFO(slurp(err));
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
  };
  SECTION("simulate: nothing cached") {
    const fs::path cache = scratch() / "sigint_generate_cache", err = scratch() / "sigint_generate_err.txt";
    interrupt({"simulate", chain.c_str(), "--t-end", "1", "--integrator", "implicit"}, cache, err, 0);
    CHECK(slurp(err).find("error: interrupted by SIGINT while generating " + chain +
                          "; nothing was cached\n") != std::string::npos);
    if (fs::exists(cache))
      for (const auto& entry : fs::recursive_directory_iterator(cache)) {
        INFO(entry.path());
        CHECK(entry.is_directory());
      }
  }
  SECTION("generate -o: nothing written") {
    const fs::path out = scratch() / "sigint_generate_out", err = scratch() / "sigint_generate_err2.txt";
    fs::remove_all(out);
    interrupt({"generate", chain.c_str(), "--jacobians", "-o", out.c_str()}, scratch() / "unused_cache", err,
              700000);
    CHECK(slurp(err) == "error: interrupted by SIGINT while generating " + chain + "; nothing was written\n");
    CHECK(!fs::exists(out));
  }
}

// ---- results a person can look at ----

namespace {

/// The CSV as a header and rows of numbers.
std::pair<std::vector<std::string>, std::vector<std::vector<double>>> read_csv(const std::string& text) {
  std::vector<std::string> lines = lines_of(text), header;
  std::vector<std::vector<double>> rows;
  std::istringstream h(lines.at(0));
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  for (std::size_t k = 1; k < lines.size(); ++k) {
    std::vector<double> row;
    std::istringstream r(lines[k]);
    for (std::string cell; std::getline(r, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return {header, rows};
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  REQUIRE(it != header.end());
  return static_cast<std::size_t>(it - header.begin());
}

}  // namespace

TEST_CASE("simulate --energies: T, V and T+V columns, by hand for the pendulum", "[cli]") {
  const Result r = kanegen("simulate " + model("simple_pendulum.json") +
                           " --t-end 1 --dt 0.25 --energies --set m=2 --set l=1.5 --quiet");
  REQUIRE(r.status == 0);
  const auto [header, rows] = read_csv(r.out);
  const std::size_t q = column(header, "pivot"), u = column(header, "pivot_dot");
  const std::size_t T = column(header, "kinetic_energy"), V = column(header, "potential_energy"),
                    E = column(header, "total_energy");
  CHECK(E == header.size() - 1);
  REQUIRE(rows.size() == 5);
  const double m = 2, l = 1.5, g = 9.81;  // a point mass m at distance l below the pivot
  for (const auto& row : rows) {
    INFO("t=" << row[0]);
    CHECK(row[T] == Approx(0.5 * m * l * l * row[u] * row[u]).epsilon(1e-12).margin(1e-14));
    CHECK(row[V] == Approx(-m * g * l * std::cos(row[q])).epsilon(1e-12));
    CHECK(row[E] == Approx(row[T] + row[V]).epsilon(1e-14));
    CHECK(row[E] == Approx(-m * g * l * std::cos(0.5)).epsilon(1e-7));  // conserved, from rest at q0 = 0.5
  }
}

TEST_CASE("simulate --energies agrees with the runner's eval at the same states", "[cli]") {
  const std::string pendulum = model("double_pendulum.json");
  const Result r = kanegen("simulate " + pendulum + " --t-end 0.5 --dt 0.25 --energies --quiet");
  REQUIRE(r.status == 0);
  const auto [header, rows] = read_csv(r.out);
  for (const auto& row : rows) {
    char args[400];
    std::snprintf(args, sizeof args, " --q %.17g,%.17g --u %.17g,%.17g --quiet", row[1], row[2], row[3],
                  row[4]);
    const Result e = kanegen("eval " + pendulum + args);
    REQUIRE(e.status == 0);
    const auto j = nlohmann::json::parse(e.out);
    CHECK(row[column(header, "kinetic_energy")] == Approx(j["kinetic_energy"].get<double>()).epsilon(1e-14));
    CHECK(row[column(header, "potential_energy")] ==
          Approx(j["potential_energy"].get<double>()).epsilon(1e-14));
  }
}

TEST_CASE("simulate --stats ends with a summary: steps, final time, energy drift, loop residual", "[cli]") {
  const Result r = kanegen("simulate " + model("simple_pendulum.json") + " --t-end 1 --stats --quiet");
  REQUIRE(r.status == 0);
  const std::string summary = lines_of(r.err).back();
  INFO(r.err);
  CHECK(summary.rfind("summary: ", 0) == 0);
  CHECK(summary.find(" steps to t=1; T+V changed by at most ") != std::string::npos);
  const double drift = std::stod(summary.substr(summary.find("at most ") + 8));
  CHECK(drift < 1e-6);
  CHECK(summary.find("loop residual") == std::string::npos);
  CHECK(summary.find("), the energy drift") != std::string::npos);
  // A prescribed hub puts work in: its change of T + V is not called a drift.
  const Result driven =
      kanegen("simulate " + model("spin_up_beam_linear.json") + " --t-end 0.5 --stats --quiet");
  REQUIRE(driven.status == 0);
  CHECK(lines_of(driven.err)
            .back()
            .find("not a drift: the model has dampers, efforts, body-fixed forces or "
                  "prescribed motions (--energies adds their work W_nc") != std::string::npos);
  const Result loop = kanegen("simulate " + model("four_bar.json") + " --t-end 0.2 --stats --quiet");
  REQUIRE(loop.status == 0);
  const std::string with_loops = lines_of(loop.err).back();
  REQUIRE(with_loops.find("; largest loop residual |phi| ") != std::string::npos);
  CHECK(std::stod(with_loops.substr(with_loops.find("|phi| ") + 6)) < 1e-8);
  // Without a terminal there is no progress line (no carriage return).
  CHECK(r.err.find('\r') == std::string::npos);
}

TEST_CASE("simulate keeps stdout for the CSV, and --help says the --stats summary goes to stderr", "[cli]") {
  // A user piping the CSV (| cat, > file) gets the summary on stderr, as on a terminal: --help says so.
  const std::string help = kanegen("simulate --help").out;
  CHECK(help.find("CSV on stdout") != std::string::npos);
  CHECK(help.find("summary line") != std::string::npos);
  CHECK(help.find("2>&1") != std::string::npos);
  // Here stdout and stderr are pipes: stdout is the CSV alone, the stats and summary are on stderr.
  const Result r = kanegen("simulate " + model("simple_pendulum.json") + " --t-end 0.1 --stats --quiet");
  REQUIRE(r.status == 0);
  const auto [header, rows] = read_csv(r.out);
  CHECK(rows.size() == 11);
  CHECK(r.out.find("summary") == std::string::npos);
  CHECK(lines_of(r.err).back().rfind("summary: ", 0) == 0);
}

namespace {

/// The width and height of a PNG from its IHDR chunk, after checking the
/// signature; {0, 0} if it is not a PNG.
std::pair<unsigned, unsigned> png_size(const std::string& bytes) {
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0 || bytes.compare(12, 4, "IHDR") != 0)
    return {0, 0};
  const auto be32 = [&](std::size_t at) {
    unsigned v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = v << 8 | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

}  // namespace

TEST_CASE("kanegen plot draws columns of a result into a PNG with gnuplot", "[cli]") {
  const fs::path csv = scratch() / "plot_me.csv";
  REQUIRE(kanegen("simulate " + model("simple_pendulum.json") + " --t-end 2 --energies --quiet -o " +
                  csv.string())
              .status == 0);
  const fs::path png = scratch() / "figures" / "pendulum.png";
  const Result r = kanegen("plot " + csv.string() +
                           " --y pivot --y total_energy --width 640 --height 480 -o " + png.string());
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err == "kanegen: wrote " + png.string() + " (2 columns against t)\n");
  CHECK(png_size(slurp(png)) == std::make_pair(640u, 480u));
  CHECK(fs::file_size(png) > 5000);  // lines and labels drawn, not an empty frame
  // The default: every column but t, into RESULT.png.
  REQUIRE(kanegen("plot " + csv.string() + " --quiet").status == 0);
  CHECK(png_size(slurp(scratch() / "plot_me.png")) == std::make_pair(1000u, 600u));

  const Result unknown =
      kanegen("plot " + csv.string() + " --y pivott -o " + (scratch() / "no.png").string());
  CHECK(unknown.status == 2);
  CHECK(unknown.err == "error: no column 'pivott' in " + csv.string() + "; did you mean 'pivot'?\n");
  CHECK(!fs::exists(scratch() / "no.png"));
  std::ofstream(scratch() / "not_a_result.csv") << "a,b\n1,2\n";
  const Result foreign = kanegen("plot " + (scratch() / "not_a_result.csv").string());
  CHECK(foreign.status == 1);
  CHECK(foreign.err.find("the first line is not a header starting with t") != std::string::npos);
}

TEST_CASE("kanegen plot refuses a file name with a line break (gnuplot would run the next line)", "[cli]") {
  // The file name is the plot's default title: a line break in it ends
  // gnuplot's command and the next line runs as one (system() runs shell
  // commands). Checked with gnuplot 5.4: the old quoting ran it.
  // (A file name holds no '/': the marker is made in the working directory.)
  const fs::path marker = fs::current_path() / "gnuplot_ran_it";
  fs::remove(marker);
  const fs::path csv = scratch() / "a\nsystem(\"touch gnuplot_ran_it\")\n.csv";
  std::ofstream(csv) << "t,a\n0,1\n1,2\n";
  const Result r = kanegen("plot '" + csv.string() + "' -o " + (scratch() / "hostile.png").string());
  INFO(r.err);
  CHECK(r.status != 0);
  CHECK(r.err.find("holds a control character, which cannot be passed to gnuplot; rename it") !=
        std::string::npos);
  CHECK(!fs::exists(marker));
  CHECK(!fs::exists(scratch() / "hostile.png"));
}

TEST_CASE("simulate --plot simulates and plots in one step and stdout still gets the CSV", "[cli]") {
  const fs::path png = scratch() / "one_step" / "double.png";
  const Result r =
      kanegen("simulate " + model("double_pendulum.json") + " --t-end 1 --quiet --plot " + png.string());
  REQUIRE(r.status == 0);
  CHECK(r.out.rfind("t,shoulder,elbow,", 0) == 0);
  CHECK(lines_of(r.out).size() == 102);
  CHECK(png_size(slurp(png)).first == 1000u);
  for (const auto& entry : fs::directory_iterator(png.parent_path()))  // no temporary CSV left
    CHECK(entry.path().filename() == "double.png");
}

TEST_CASE("simulate --plot without gnuplot says so before it builds or runs anything", "[cli]") {
  const fs::path png = scratch() / "no_gnuplot" / "double.png";
  const fs::path err = scratch() / "no_gnuplot_err.txt", cache = scratch() / "no_gnuplot_cache";
  // No gnuplot on this PATH, and no compiler either: only a check made before the build passes.
  const std::string command = "PATH=/nonexistent KANEGEN_CACHE_DIR='" + cache.string() + "' " + KANEGEN_EXE +
                              " simulate " + model("double_pendulum.json") + " --t-end 1 --plot " +
                              png.string() + " >/dev/null 2>" + err.string();
  const int status = std::system(command.c_str());
  CHECK(status != 0);
  const std::string said = slurp(err);
  CHECK(said.find("error: gnuplot not found on the PATH; install it (Debian: apt-get install gnuplot-nox)") !=
        std::string::npos);
  CHECK(said.find("compiling") == std::string::npos);
  CHECK_FALSE(fs::exists(png.parent_path()));
  CHECK_FALSE(fs::exists(cache));
}

TEST_CASE("Ctrl-C during a long verify: interrupted, exit 130, as a simulation", "[cli]") {
  const fs::path cache = scratch() / "verify_sigint_cache";
  const fs::path out = scratch() / "verify_sigint_out.txt", err = scratch() / "verify_sigint_err.txt";
  const std::string pendulum = model("simple_pendulum.json");
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    setpgid(0, 0);
    setenv("KANEGEN_CACHE_DIR", cache.c_str(), 1);
    if (!std::freopen(out.c_str(), "w", stdout) || !std::freopen(err.c_str(), "w", stderr)) _exit(126);
    execl(KANEGEN_EXE, KANEGEN_EXE, "verify", pendulum.c_str(), "--samples", "10000000", "--trajectories",
          "0", static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  for (int i = 0; i < 600 && slurp(err).find("random states") == std::string::npos; ++i) usleep(25000);
  REQUIRE(slurp(err).find("random states") != std::string::npos);
  usleep(300000);
  kill(-pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  INFO(slurp(err));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(lines_of(slurp(err)).back() ==
        "error: interrupted by SIGINT; kanegen verify stopped before its result");
  CHECK(slurp(out).empty());
}

TEST_CASE("urdfdom's warnings are said, once each", "[cli]") {
  const std::string urdf = std::string(KANEGEN_BAD_MODELS_DIR) + "/../../model/data/undefined_material.urdf";
  const Result r = kanegen("generate " + urdf + " --quiet -o " + (scratch() / "warned").string());
  CHECK(r.status == 0);
  CHECK(r.err == "warning: " + urdf + ": urdfdom: link 'arm' material 'steel' undefined.\n");
}

TEST_CASE("a long run shows one updating progress line on a terminal and nothing on a file", "[cli]") {
  if (std::system("command -v script >/dev/null 2>&1") != 0) {
    WARN("no script(1) to give kanegen a terminal: skipped");
    return;
  }
  // RK4 and genalpha take one step per output row (dt), so the steps shown
  // at time t are t / dt; a count of right-hand sides would be several times
  // as many. The rows go to /dev/null, the progress line to the terminal.
  for (const auto& [integrator, t_end] : {std::pair{"rk4", "40"}, std::pair{"genalpha", "10"}}) {
    const fs::path typescript = scratch() / (std::string("typescript_") + integrator);
    const std::string run = std::string(KANEGEN_EXE) + " simulate " + model("simple_pendulum.json") +
                            " --integrator " + integrator + " --t-end " + t_end +
                            " --dt 0.0002 --quiet -o - >/dev/null";
    // script(1) runs the command on a pseudo-terminal, as a user's shell would.
    // The line appears after 1 s; a shorter quiet start makes the test
    // independent of the machine's speed.
    const std::string command = "KANEGEN_PROGRESS_AFTER=0 KANEGEN_CACHE_DIR='" KANEGEN_SCRATCH_DIR
                                "/cache' script -qec '" +
                                run + "' " + typescript.string() + " >/dev/null 2>&1";
    INFO(integrator);
    const int status = std::system(command.c_str());
    const std::string shown = slurp(typescript);
    // A failure shows what the terminal got (it failed once under load, cause unknown; not reproduced in
    // 36 runs at load 7-8.5, alone, niced, and among the cli tests with a cold cache).
    INFO("exit status " << status << "; the terminal got:\n" << shown);
    REQUIRE(status == 0);
    const auto first = shown.find("\r\033[Ksimulate: t = ");
    REQUIRE(first != std::string::npos);
    CHECK(shown.find('\n', first) > shown.rfind("\r\033[K"));  // one line, erased at the end
    const std::regex line("simulate: t = ([0-9.e+]+) of " + std::string(t_end) +
                          " s, wall [0-9.]+ s, ([0-9]+) steps");
    int lines_seen = 0;
    for (auto it = std::sregex_iterator(shown.begin() + first, shown.end(), line);
         it != std::sregex_iterator(); ++it, ++lines_seen) {
      const double t = std::stod((*it)[1]), steps = std::stod((*it)[2]);
      INFO(it->str());
      CHECK(std::abs(steps * 0.0002 - t) <= 1e-5 * t + 0.0002);  // t has 6 digits
    }
    CHECK(lines_seen > 0);
  }
  // The same run on a file, with the same quiet start: nothing.
  setenv("KANEGEN_PROGRESS_AFTER", "0", 1);
  const Result piped =
      kanegen("simulate " + model("simple_pendulum.json") +
              " --integrator rk4 --t-end 40 --dt 0.0002 --quiet -o " + (scratch() / "long2.csv").string());
  unsetenv("KANEGEN_PROGRESS_AFTER");
  CHECK(piped.status == 0);
  CHECK(piped.err.empty());
}

TEST_CASE("a number out of range is refused without the range's 309 digits", "[cli]") {
  const Result r = kanegen("verify " + model("simple_pendulum.json") + " --duration 0");
  CHECK(r.status != 0);
  CHECK(r.err == "--duration: needs a positive number, got '0'\nRun with --help for more information.\n");
  const Result negative = kanegen("verify " + model("simple_pendulum.json") + " --trajectories -1");
  CHECK(negative.status != 0);
  CHECK(negative.err.rfind("--trajectories: needs a number >= 0, got '-1'\n", 0) == 0);
}

TEST_CASE("a loop model's header compares its saddle-point solve with the other solve alone", "[cli]") {
  // The count in parentheses is the solve's share of forward_dynamics, and the other method's is the
  // other solve's alone (the rest of the kernel is the same): "dense: N" read as a total looked smaller.
  const fs::path dir = scratch() / "gen_saddle";
  REQUIRE(kanegen("generate " + model("four_bar.json") + " -o " + dir.string()).status == 0);
  std::smatch match;
  const std::string header = slurp(dir / "four_bar.hpp");
  REQUIRE(std::regex_search(
      header, match,
      std::regex("forward_dynamics: ([0-9]+) \\(([0-9]+) of them in the saddle-point solve, "
                 "a sparse LDL\\^T; the dense solve would take ([0-9]+) in their place\\)")));
  CHECK(std::stol(match[2]) < std::stol(match[3]));
  CHECK(std::stol(match[2]) < std::stol(match[1]));
}

TEST_CASE("generate --dynamics picks forward_dynamics's method, states it and refuses what it cannot solve",
          "[cli][recursive]") {
  const fs::path dir = scratch() / "gen_dynamics";
  // double_pendulum: auto keeps the composite solve (fewer operations at 2 joints) and names both counts.
  const Result automatic =
      kanegen("generate " + model("double_pendulum.json") + " -o " + (dir / "auto").string());
  REQUIRE(automatic.status == 0);
  CHECK(automatic.out.find("forward_dynamics: composite inertias (recursive ") != std::string::npos);
  const std::string header = slurp(dir / "auto" / "double_pendulum.hpp");
  CHECK(std::regex_search(header, std::regex("forward_dynamics: [0-9]+ \\(composite inertias, [0-9]+ of them "
                                             "in LDL\\^T; recursive: [0-9]+\\)")));
  const Result recursive = kanegen("generate " + model("double_pendulum.json") + " -o " +
                                   (dir / "recursive").string() + " --dynamics recursive");
  REQUIRE(recursive.status == 0);
  const std::string recursive_header = slurp(dir / "recursive" / "double_pendulum.hpp");
  CHECK(std::regex_search(recursive_header,
                          std::regex("forward_dynamics: [0-9]+ \\(recursive; composite inertias and LDL\\^T: "
                                     "[0-9]+\\)")));
  CHECK(slurp(dir / "recursive" / "double_pendulum.cpp").find("Articulated-body recursion") !=
        std::string::npos);
  CHECK(slurp(dir / "auto" / "double_pendulum.cpp").find("Articulated-body recursion") == std::string::npos);

  // Flexible bodies are in the recursion (their elastic speeds a block per body).
  const Result flexible = kanegen("generate " + model("spatial_arm2.json") + " -o " +
                                  (dir / "flexible").string() + " --dynamics recursive");
  CHECK(flexible.status == 0);
  CHECK(slurp(dir / "flexible" / "spatial_arm2.cpp").find("Articulated-body recursion") != std::string::npos);

  // Loops and prescribed motions are refused, naming why and the way out; nothing written.
  const Result loops = kanegen("generate " + model("four_bar.json") + " -o " + (dir / "loops").string() +
                               " --dynamics recursive");
  CHECK(loops.status == 2);
  CHECK(
      loops.err.find("four_bar.json: /loops/0: --dynamics recursive is for open trees, and this model "
                     "closes 1 loop(s) (their constraint forces need the saddle-point solve); use --dynamics "
                     "composite, or auto (the default), which picks composite here") != std::string::npos);
  const fs::path prescribed = scratch() / "prescribed_hub.json";
  std::ofstream(prescribed) << R"({"format": "kanegen-model", "version": 1, "name": "hub",
    "bodies": [{"name": "hub", "mass": 1, "inertia": {"ixx": 0.1, "iyy": 0.1, "izz": 0.1}},
               {"name": "rod", "mass": 1, "com": [0.5, 0, 0], "inertia": {"ixx": 0.1, "iyy": 0.1, "izz": 0.1}}],
    "joints": [{"name": "spin", "type": "revolute", "parent": "ground", "child": "hub", "prescribed": "t^2"},
               {"name": "swing", "type": "revolute", "parent": "hub", "child": "rod", "axis": [0, 1, 0]}]})";
  const Result given = kanegen("generate " + prescribed.string() + " -o " + (dir / "prescribed").string() +
                               " --dynamics recursive");
  CHECK(given.status == 2);
  CHECK(given.err.find(
            "prescribed_hub.json: /joints/0/prescribed: --dynamics recursive solves for every speed, "
            "and joint 'spin' has a prescribed motion") != std::string::npos);
  CHECK(kanegen("generate " + prescribed.string() + " -o " + (dir / "prescribed").string()).status == 0);
  // A point mass on the axis of its hinge: no inertia about it in any state, so no 1/D; composite still
  // generates.
  const fs::path point = scratch() / "point_on_axis.json";
  std::ofstream(point) << R"({"format": "kanegen-model", "version": 1, "name": "point_on_axis",
    "bodies": [{"name": "a", "mass": 1, "com": [0.5, 0, 0], "inertia": {"ixx": 0.1, "iyy": 0.1, "izz": 0.1}},
               {"name": "b", "mass": 1, "inertia": {"ixx": 0, "iyy": 0, "izz": 0}}],
    "joints": [{"name": "j1", "type": "revolute", "parent": "ground", "child": "a", "axis": [0, 1, 0]},
               {"name": "j2", "type": "revolute", "parent": "a", "child": "b", "axis": [0, 1, 0]}]})";
  const Result zero =
      kanegen("generate " + point.string() + " -o " + (dir / "point").string() + " --dynamics recursive");
  CHECK(zero.status == 2);
  CHECK(
      zero.err.find(
          "point_on_axis.json: /joints/1: --dynamics recursive cannot solve this model: joint 'j2' moves no "
          "inertia about or along its axis in any state (the recursion divides by it); use "
          "--dynamics composite, or auto (the default)") != std::string::npos);
  CHECK(!fs::exists(dir / "point"));
  CHECK(kanegen("generate " + point.string() + " -o " + (dir / "point").string()).status == 0);
  CHECK(kanegen("generate " + model("arm7.urdf") + " -o " + dir.string() + " --dynamics fast").status != 0);
  CHECK(!fs::exists(dir / "loops"));
  CHECK(kanegen("generate --help").out.find("--dynamics") != std::string::npos);
  CHECK(kanegen("simulate --help").out.find("--dynamics") != std::string::npos);
}

TEST_CASE("a subtree without mass under the recursive forward_dynamics names its joint", "[cli][recursive]") {
  // Both rods massless: the recursion's pivot of the outer joint (leaves first) is zero.
  const Result r = kanegen("simulate " + model("double_pendulum.json") +
                           " --dynamics recursive --t-end 1 --quiet --set m1=0 --set m2=0 -o " +
                           (scratch() / "massless_recursive.csv").string());
  CHECK(r.status == 1);
  CHECK(r.err.find("error: mass matrix is not positive definite at coordinate 'elbow' (pivot 2") == 0);
}

TEST_CASE("verify reports a failed numeric saddle-point solve as a mismatch and does not crash", "[cli]") {
  // The rigid slider-crank with its rod and slider massless (parameters, so
  // the generator's check of literal masses lets it through; --spread 0
  // keeps them 0): M is singular, so the numeric path has no lambda. verify
  // read past the end of lambda's empty magnitudes (SIGSEGV); the trigger
  // was the stiffened solid slider-crank's indefinite M, which the elastic
  // mass to second order has removed (docs/flexible-bodies.md).
  nlohmann::json m;
  std::ifstream(model("slider_crank.json")) >> m;
  for (const char* mass : {"m2", "m3", "J2"}) m["parameters"][mass] = 0.0;
  const fs::path file = scratch() / "massless_slider_crank.json";
  std::ofstream(file) << m.dump(1);
  const Result r = kanegen("verify " + file.string() + " --samples 2 --trajectories 0 --spread 0");
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.out.find("M positive definite") != std::string::npos);
  CHECK(r.out.find("MISMATCH") != std::string::npos);
  CHECK(r.err.find("error: lambda") != std::string::npos);
}
