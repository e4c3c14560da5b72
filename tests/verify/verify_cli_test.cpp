// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen verify as a user runs it: the JSON report, --help, kernels of
// another model, and the corruption tests: a copy of generated kernels with
// one term altered must fail, naming the quantity.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "../support/run_kanegen.hpp"

namespace fs = std::filesystem;

namespace {

using kanegen_test::Result;
using kanegen_test::slurp;

fs::path scratch() {
  static const fs::path dir = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  return dir;
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// Runs kanegen (arguments in shell syntax) with a private runner cache.
Result kanegen(const std::string& args) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_CACHE, scratch(), args);
}

std::string source(const std::string& relative) { return std::string(KANEGEN_SOURCE_DIR) + "/" + relative; }

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// Generates the model's kernels into a fresh scratch directory.
fs::path generate(const std::string& model, const std::string& name) {
  const fs::path dir = scratch() / name;
  fs::remove_all(dir);
  const Result r = kanegen("generate " + source(model) + " -o " + dir.string() + " --quiet");
  REQUIRE(r.status == 0);
  return dir;
}

/// Replaces, inside the body of the function `function` of `file`, the first
/// match of `pattern` by `replacement` (regex syntax, $& = the match).
void corrupt(const fs::path& file, const std::string& function, const std::string& pattern,
             const std::string& replacement) {
  std::string text = slurp(file);
  const std::size_t begin = text.find("\n" + function + "(");
  REQUIRE(begin != std::string::npos);
  const std::size_t end = text.find("\n}\n", begin);
  REQUIRE(end != std::string::npos);
  std::string body = text.substr(begin, end - begin);
  std::smatch match;
  INFO(function << " has no match of " << pattern << ":\n" << body);
  REQUIRE(std::regex_search(body, match, std::regex(pattern)));
  const std::string altered =
      std::regex_replace(body, std::regex(pattern), replacement, std::regex_constants::format_first_only);
  REQUIRE(altered != body);
  write(file, text.substr(0, begin) + altered + text.substr(end));
}

/// Scales, inside the body of `function`, the first decimal literal that is
/// followed by `after` (a regex) and is at least `least` in magnitude.
void scale_literal(const fs::path& file, const std::string& function, const std::string& after, double least,
                   double factor) {
  std::string text = slurp(file);
  const std::size_t begin = text.find("\n" + function + "(");
  REQUIRE(begin != std::string::npos);
  const std::size_t end = text.find("\n}\n", begin);
  REQUIRE(end != std::string::npos);
  const std::regex literal("\\b[0-9]+\\.?[0-9]*(e[-+]?[0-9]+)?(?=" + after + ")");
  for (auto it = std::sregex_iterator(text.begin() + begin, text.begin() + end, literal);
       it != std::sregex_iterator(); ++it) {
    const double value = std::stod(it->str());
    if (std::abs(value) < least) continue;
    char altered[64];
    std::snprintf(altered, sizeof altered, "%.17g", value * factor);
    const std::size_t at = begin + it->position();
    write(file, text.substr(0, at) + altered + text.substr(at + it->length()));
    return;
  }
  FAIL("no literal of at least " << least << " before " << after << " in " << function);
}

}  // namespace

TEST_CASE("verify --json reports every quantity and passes", "[verify]") {
  const Result r =
      kanegen("verify " + source("models/double_pendulum.json") + " --samples 20 --seed 5 --json");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["passed"].get<bool>());
  CHECK(j["model"] == "double_pendulum");
  CHECK(j["samples"] == 20);
  CHECK(j["seed"] == 5);
  CHECK(j["failures"].empty());
  std::vector<std::string> names;
  for (const auto& q : j["quantities"]) {
    names.push_back(q["quantity"]);
    CHECK(q["passed"].get<bool>());
    if (q["applicable"].get<bool>()) CHECK(q["rel_error"].get<double>() <= q["tolerance"].get<double>());
  }
  for (const char* quantity :
       {"mass_matrix", "forcing", "udot", "kinetic_energy", "potential_energy", "outputs", "M symmetric",
        "M positive definite", "d2T/du2", "power balance", "Jacobians", "inverse_dynamics", "gravity",
        "nonconservative_power", "controller kernels"})
    CHECK(std::find(names.begin(), names.end(), quantity) != names.end());
  // A kernel that kernels.def names no check for has a row saying so.
  const auto momentum =
      std::find_if(j["quantities"].begin(), j["quantities"].end(),
                   [](const nlohmann::json& q) { return q["quantity"] == "generalized_momentum"; });
  REQUIRE(momentum != j["quantities"].end());
  CHECK_FALSE((*momentum)["applicable"].get<bool>());
  CHECK(contains(r.err, "kanegen: verify:"));  // progress on stderr
}

TEST_CASE("verify is reproducible for a seed and prints a table", "[verify]") {
  const std::string args =
      "verify " + source("models/simple_pendulum.json") + " --samples 10 --seed 9 --quiet";
  const Result a = kanegen(args), b = kanegen(args);
  REQUIRE(a.status == 0);
  CHECK(a.err.empty());
  CHECK(contains(a.out, "mass_matrix"));
  CHECK(contains(a.out, "verified"));
  // Identical apart from the timing line.
  const auto table = [](const std::string& s) { return s.substr(0, s.rfind("verified")); };
  CHECK(table(a.out) == table(b.out));
}

TEST_CASE("verify --help and usage errors", "[verify]") {
  const Result top = kanegen("--help");
  CHECK(contains(top.out, "verify"));
  const Result help = kanegen("verify --help");
  CHECK(help.status == 0);
  for (const char* option :
       {"--samples", "--seed", "--rtol", "--json", "--kernels", "--jacobians", "--controller"})
    CHECK(contains(help.out, option));
  CHECK(kanegen("verify").status != 0);
  CHECK(kanegen("verify " + source("models/simple_pendulum.json") + " --samples 0").status != 0);
  CHECK(kanegen("verify " + source("models/simple_pendulum.json") + " --kernels /no/such/dir").status != 0);
}

TEST_CASE("verify --kernels of another model is a clear error", "[verify]") {
  const fs::path dir = generate("models/simple_pendulum.json", "other");
  const Result r =
      kanegen("verify " + source("models/double_pendulum.json") + " --kernels " + dir.string() + " --quiet");
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: the kernels do not match"));
}

TEST_CASE("verify --kernels with --dynamics is refused, not ignored", "[verify]") {
  const fs::path dir = generate("models/simple_pendulum.json", "dynamics");
  const Result r = kanegen("verify " + source("models/simple_pendulum.json") + " --kernels " + dir.string() +
                           " --dynamics recursive --quiet");
  CHECK(r.status == 2);
  CHECK(contains(r.err, "error: --dynamics has no effect with --kernels"));
  CHECK(contains(r.err, "kanegen generate --dynamics recursive"));
}

TEST_CASE("verify refuses loops that are dependent everywhere, naming the fix", "[verify][loops]") {
  // The four-bar with a spatial revolute: its out-of-plane rows vanish identically.
  nlohmann::json model = nlohmann::json::parse(slurp(source("models/four_bar.json")));
  model["loops"][0]["planar"] = false;
  const fs::path file = scratch() / "four_bar_redundant.json";
  write(file, model.dump(2));
  const Result r = kanegen("verify " + file.string() + " --quiet");
  CHECK(r.status == 2);
  CHECK(contains(r.err, file.string() + ": /loops: the loop equations are (nearly) dependent at 1000 random "
                                        "states in a row"));
  CHECK(contains(r.err, "\"planar\": true"));
  CHECK(r.out.empty());
}

TEST_CASE("verify --kernels passes on an unaltered copy", "[verify][corruption]") {
  const fs::path dir = generate("tests/data/models/forced_cart_pendulum.json", "clean");
  const Result r = kanegen("verify " + source("tests/data/models/forced_cart_pendulum.json") + " --kernels " +
                           dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 0);
}

TEST_CASE("corruption: half the damping in forcing fails, naming forcing", "[verify][corruption]") {
  const fs::path dir = generate("tests/data/models/forced_cart_pendulum.json", "damping");
  corrupt(dir / "forced_cart_pendulum.cpp", "void forcing", "\\bp\\.c\\b", "(0.5*$&)");
  const Result r = kanegen("verify " + source("tests/data/models/forced_cart_pendulum.json") + " --kernels " +
                           dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: forcing [1] (pivot)"));
  CHECK(contains(r.err, "state t="));
  CHECK(contains(r.out, "FAIL"));
  CHECK(contains(r.out, "MISMATCH"));
  // udot comes from forward_dynamics, a separate kernel: it still agrees.
  CHECK_FALSE(contains(r.err, "error: udot"));
}

TEST_CASE("corruption: one literal of mass_matrix off by 1e-4 fails, naming mass_matrix",
          "[verify][corruption]") {
  const fs::path dir = generate("models/arm7.urdf", "literal");
  // The first decimal literal of the kernel that is not tiny, scaled by 1 + 1e-4.
  const fs::path file = dir / "arm7.cpp";
  std::string text = slurp(file);
  const std::size_t begin = text.find("\nvoid mass_matrix(");
  REQUIRE(begin != std::string::npos);
  const std::size_t end = text.find("\n}\n", begin);
  const std::regex literal("\\b[0-9]+\\.[0-9]+(e[-+]?[0-9]+)?");
  std::size_t at = std::string::npos, length = 0;
  double value = 0;
  for (auto it = std::sregex_iterator(text.begin() + begin, text.begin() + end, literal);
       it != std::sregex_iterator(); ++it) {
    value = std::stod(it->str());
    if (value >= 0.05) {
      at = begin + it->position();
      length = it->length();
      break;
    }
  }
  REQUIRE(at != std::string::npos);
  char altered[64];
  std::snprintf(altered, sizeof altered, "%.17g", value * (1 + 1e-4));
  write(file, text.substr(0, at) + altered + text.substr(at + length));
  const Result r =
      kanegen("verify " + source("models/arm7.urdf") + " --kernels " + dir.string() + " --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: mass_matrix"));
  CHECK(contains(r.err, "error: d2T/du2"));  // M no longer the Hessian of the (unaltered) kinetic energy
}

TEST_CASE("corruption: a wrong term in forward_dynamics fails udot and the power balance",
          "[verify][corruption]") {
  const fs::path dir = generate("models/double_pendulum.json", "dynamics");
  corrupt(dir / "double_pendulum.cpp", "int forward_dynamics", "\\bp\\.m2\\b", "(1.01*$&)");
  const Result r = kanegen("verify " + source("models/double_pendulum.json") + " --kernels " + dir.string() +
                           " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: udot"));
  CHECK(contains(r.err, "error: power balance"));
}

TEST_CASE("corruption: a wrong kinetic or potential energy fails, naming it", "[verify][corruption]") {
  const fs::path dir = generate("models/double_pendulum.json", "energy");
  corrupt(dir / "double_pendulum.cpp", "double potential_energy", "\\bp\\.m1\\b", "(1.001*$&)");
  corrupt(dir / "double_pendulum.cpp", "double kinetic_energy", "\\bp\\.m2\\b", "(1.001*$&)");
  const Result r = kanegen("verify " + source("models/double_pendulum.json") + " --kernels " + dir.string() +
                           " --samples 20 --quiet --json");
  CHECK(r.status == 1);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK_FALSE(j["passed"].get<bool>());
  std::vector<std::string> failed;
  for (const auto& q : j["quantities"])
    if (!q["passed"].get<bool>()) failed.push_back(q["quantity"]);
  CHECK(std::find(failed.begin(), failed.end(), "potential_energy") != failed.end());
  CHECK(std::find(failed.begin(), failed.end(), "kinetic_energy") != failed.end());
  CHECK(std::find(failed.begin(), failed.end(), "d2T/du2") != failed.end());
  CHECK(std::find(failed.begin(), failed.end(), "mass_matrix") == failed.end());
}

namespace {

/// The names of the failed quantities of a --json report.
std::vector<std::string> failed_quantities(const std::string& report) {
  std::vector<std::string> failed;
  const nlohmann::json j = nlohmann::json::parse(report);
  for (const auto& q : j["quantities"])
    if (!q["passed"].get<bool>()) failed.push_back(q["quantity"]);
  return failed;
}

}  // namespace

TEST_CASE("corruption: a wrong sign in inverse_dynamics, gravity or nonconservative_power fails its row",
          "[verify][corruption][controller]") {
  const fs::path dir = generate("models/double_pendulum.json", "controller_always");
  const fs::path file = dir / "double_pendulum.cpp";
  corrupt(file, "void inverse_dynamics", "\\budot\\[0\\]", "(-$&)");
  corrupt(file, "void gravity", "\\bp\\.m1\\b", "(-$&)");
  corrupt(file, "double nonconservative_power", "\\bp\\.c2\\b", "(-$&)");
  const Result r = kanegen("verify " + source("models/double_pendulum.json") + " --kernels " + dir.string() +
                           " --samples 20 --quiet --json");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: inverse_dynamics ["));
  CHECK(contains(r.err, "error: gravity [0] (shoulder)"));
  CHECK(contains(r.err, "error: nonconservative_power"));
  // The kernels are separate: nothing else fails (the power balance uses the numeric P_nc).
  const std::vector<std::string> failed = failed_quantities(r.out);
  CHECK(failed == std::vector<std::string>{"inverse_dynamics", "gravity", "nonconservative_power"});
}

TEST_CASE("verify --controller: a wrong sign in each controller kernel fails its row, naming it",
          "[verify][corruption][controller]") {
  const fs::path dir = scratch() / "controller";
  fs::remove_all(dir);
  REQUIRE(kanegen("generate " + source("models/double_pendulum.json") + " -o " + dir.string() +
                  " --controller --quiet")
              .status == 0);
  const std::string verify = "verify " + source("models/double_pendulum.json") + " --kernels " +
                             dir.string() + " --samples 20 --quiet";
  {
    const Result clean = kanegen(verify + " --controller");
    INFO(clean.out << clean.err);
    CHECK(clean.status == 0);
    for (const char* row : {"coriolis_matrix C u", "coriolis_matrix C + C^T", "output_jacobian ",
                            "output_jacobian_rate", "linearize A", "linearize B"})
      CHECK(contains(clean.out, row));
  }
  const fs::path file = dir / "double_pendulum.cpp";
  corrupt(file, "void coriolis_matrix", "\\bp\\.m2\\b", "(-$&)");
  corrupt(file, "void output_jacobian", "\\bp\\.l1\\b", "(-$&)");
  corrupt(file, "void output_jacobian_rate", "\\bp\\.l1\\b", "(-$&)");
  // A rigid tree's linearize: M dudot/dx = dR/dx of the residual R = f - M udot.
  corrupt(file, "int linearize", "= dRdq\\[i \\* NQ \\+ j\\]", "= -dRdq[i * NQ + j]");
  corrupt(file, "int linearize", "dRdtau\\[0\\] = 1\\.0", "dRdtau[0] = -1.0");
  const Result r = kanegen(verify + " --json");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  for (const char* row : {"coriolis_matrix C u [", "coriolis_matrix C + C^T [", "output_jacobian [",
                          "output_jacobian_rate [", "linearize A [", "linearize B ["})
    CHECK(contains(r.err, std::string("error: ") + row));
  const std::vector<std::string> failed = failed_quantities(r.out);
  CHECK(failed == std::vector<std::string>{"coriolis_matrix C u", "coriolis_matrix C + C^T",
                                           "output_jacobian", "output_jacobian_rate", "linearize A",
                                           "linearize B"});
}

TEST_CASE("verify --controller on a model with loops reports the controller rows as not applicable",
          "[verify][controller]") {
  const Result r = kanegen("verify " + source("models/four_bar.json") +
                           " --controller --samples 5 "
                           "--trajectories 0 --quiet --json");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  int rows = 0;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const auto& q : j["quantities"]) {
    const std::string name = q["quantity"];
    if (name.rfind("coriolis_matrix", 0) != 0 && name.rfind("output_jacobian", 0) != 0 &&
        name.rfind("linearize", 0) != 0)
      continue;
    ++rows;
    CHECK_FALSE(q["applicable"].get<bool>());
    CHECK(q["note"] == "not made for closed loops (docs/controllers.md)");
  }
  CHECK(rows == 6);
}

TEST_CASE("flexible: verify passes on a copy of the kernels, with elastic coordinates and node outputs",
          "[verify][flexible]") {
  const std::string model = "tests/data/models/flex_hub_planar.json";
  const fs::path dir = generate(model, "flexible_clean");
  const Result r = kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --json");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["passed"].get<bool>());
  CHECK(j["coordinates"] == 10);  // the hub, then 9 nodal coordinates of the clamped 3-element strip
  for (const auto& q : j["quantities"])
    if (q["quantity"] == "outputs") CHECK(q["compared"] == 20);
}

TEST_CASE("corruption: one stiffness term of a flexible forcing kernel off by 1e-6 fails, naming forcing",
          "[verify][corruption][flexible]") {
  const std::string model = "tests/data/models/flex_hub_planar.json";
  const fs::path dir = generate(model, "flexible_stiffness");
  // The first literal of at least 1000 that multiplies a coordinate: an entry of K.
  scale_literal(dir / "flex_hub_planar.cpp", "void forcing", "\\*q\\[", 1000.0, 1 + 1e-6);
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: forcing ["));
  CHECK(contains(r.err, "(arm.n"));  // an elastic row
  CHECK_FALSE(contains(r.err, "error: mass_matrix"));
  CHECK_FALSE(contains(r.err, "error: udot"));  // forward_dynamics is a separate kernel
}

TEST_CASE("corruption: a modal velocity term off by 1e-3 fails, naming forcing",
          "[verify][corruption][flexible]") {
  const std::string model = "tests/data/models/flex_hub_modal.json";
  const fs::path dir = generate(model, "flexible_modal");
  // A coefficient of the first mode's speed in the hub row's Coriolis term
  // 2 omega (C eta_dot) (the first "c*u[1] - ": the foreshortening's
  // eta_dot^T H eta_dot terms come first, too small at the sampled rates for
  // a change of 1e-3 to show).
  scale_literal(dir / "flex_hub_modal.cpp", "void forcing", "\\*u\\[1\\] - ", 0.0, 1 + 1e-3);
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: forcing ["));
  CHECK_FALSE(contains(r.err, "error: mass_matrix"));
}

TEST_CASE("corruption: a wrong elastic mass fails mass_matrix and d2T/du2",
          "[verify][corruption][flexible]") {
  const std::string model = "tests/data/models/flex_spatial_hub.json";
  const fs::path dir = generate(model, "flexible_mass");
  // The first constant entry M[r*n + c] = number; of the beam's own block (r, c >= 2: after yaw and pitch).
  const fs::path file = dir / "flex_spatial_hub.cpp";
  const std::string text = slurp(file);
  const std::size_t begin = text.find("\nvoid mass_matrix(");
  REQUIRE(begin != std::string::npos);
  const std::size_t end = text.find("\n}\n", begin);
  const int n = 20;
  const std::regex entry("M\\[([0-9]+)\\] = ([0-9]+\\.[0-9]*(e[-+]?[0-9]+)?);");
  bool done = false;
  for (auto it = std::sregex_iterator(text.begin() + begin, text.begin() + end, entry);
       it != std::sregex_iterator() && !done; ++it) {
    const int k = std::stoi((*it)[1].str());
    if (k / n < 2 || k % n < 2) continue;
    char altered[64];
    std::snprintf(altered, sizeof altered, "%.17g", std::stod((*it)[2].str()) * (1 + 1e-6));
    const std::size_t at = begin + it->position(2);
    write(file, text.substr(0, at) + altered + text.substr(at + it->length(2)));
    done = true;
  }
  REQUIRE(done);
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: mass_matrix ["));
  CHECK(contains(r.err, "(arm.n"));
  CHECK(contains(r.err, "error: d2T/du2"));  // M no longer the Hessian of the (unaltered) kinetic energy
}

TEST_CASE("corruption: a wrong prescribed acceleration fails udot, naming it",
          "[verify][corruption][flexible]") {
  const std::string model = "tests/data/models/flex_prescribed_hub.json";
  const fs::path dir = generate(model, "prescribed");
  corrupt(dir / "flex_prescribed_hub.cpp", "int forward_dynamics", "\\bap0 = (?!0\\.0;)", "$&1.001*");
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: udot [0] (hub) (prescribed acceleration)"));
  CHECK_FALSE(contains(r.err, "error: forcing"));
}

// The force elements (tests/data/models/force_elements.json): two
// spring-dampers, one to a ground point [0.7, 0.2, -1.25], and joint efforts
// A sin(w t) and F.

TEST_CASE("force elements: verify passes on a copy of the kernels", "[verify][spring][effort]") {
  const std::string model = "tests/data/models/force_elements.json";
  const fs::path dir = generate(model, "force_elements_clean");
  const Result r = kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --json");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(nlohmann::json::parse(r.out)["passed"].get<bool>());
}

TEST_CASE("corruption: a spring literal in forcing off by 1e-4 fails, naming forcing",
          "[verify][corruption][spring]") {
  const std::string model = "tests/data/models/force_elements.json";
  const fs::path dir = generate(model, "spring_literal");
  // The ground point's z, 1.25, only in the spring's terms.
  corrupt(dir / "force_elements.cpp", "void forcing", "\\b1\\.25\\b", "1.250125");
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: forcing ["));
  CHECK_FALSE(contains(r.err, "error: potential_energy"));
  CHECK_FALSE(contains(r.err, "error: udot"));  // forward_dynamics is a separate kernel
}

TEST_CASE("corruption: a spring stiffness in potential_energy fails it and the power balance",
          "[verify][corruption][spring]") {
  const std::string model = "tests/data/models/force_elements.json";
  const fs::path dir = generate(model, "spring_energy");
  corrupt(dir / "force_elements.cpp", "double potential_energy", "\\bp\\.k2\\b", "(1.001*$&)");
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: potential_energy"));
  CHECK(contains(r.err, "error: power balance"));
  CHECK_FALSE(contains(r.err, "error: forcing"));
}

TEST_CASE("corruption: a joint effort off by 1% in forward_dynamics fails udot and the power balance",
          "[verify][corruption][effort]") {
  const std::string model = "tests/data/models/force_elements.json";
  const fs::path dir = generate(model, "effort");
  corrupt(dir / "force_elements.cpp", "int forward_dynamics", "\\bp\\.A\\b", "(1.01*$&)");
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: udot"));
  CHECK(contains(r.err, "error: power balance"));
  CHECK_FALSE(contains(r.err, "error: forcing"));
}

TEST_CASE("loops: verify reports the loop kernels and the loop forces", "[verify][loops]") {
  const Result r = kanegen("verify " + source("models/four_bar.json") + " --samples 20 --json --quiet");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& q : j["quantities"])
    if (q["applicable"].get<bool>()) names.push_back(q["quantity"]);
  for (const char* quantity : {"constraints", "constraint_jacobian", "constraint_bias", "lambda", "udot",
                               "outputs", "power balance"})
    CHECK(std::find(names.begin(), names.end(), quantity) != names.end());
}

// The loop kernels are separate from constrained_dynamics (which has its own
// copy of C and gamma), so a wrong entry shows in its own row only.
TEST_CASE("corruption: a literal of constraint_jacobian off by 1e-4 fails, naming it",
          "[verify][corruption][loops]") {
  const fs::path dir = generate("models/slider_crank.json", "loop_jacobian");
  corrupt(dir / "slider_crank.cpp", "void constraint_jacobian", "= -1\\.0;", "= -1.0001;");
  const Result r = kanegen("verify " + source("models/slider_crank.json") + " --kernels " + dir.string() +
                           " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: constraint_jacobian [0,2] (E.x, slider_x)"));
  CHECK_FALSE(contains(r.err, "error: udot"));
}

TEST_CASE("corruption: a term of constraint_bias off by 1e-4 fails, naming it",
          "[verify][corruption][loops]") {
  const fs::path dir = generate("models/four_bar.json", "loop_bias");
  corrupt(dir / "four_bar.cpp", "void constraint_bias", "\\bp\\.c\\b", "(1.0001*$&)");
  const Result r = kanegen("verify " + source("models/four_bar.json") + " --kernels " + dir.string() +
                           " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: constraint_bias"));
  CHECK_FALSE(contains(r.err, "error: constraint_jacobian"));
}

namespace {

/// Generates the model's kernels with the Jacobian kernels into a fresh scratch directory.
fs::path generate_with_jacobians(const std::string& model, const std::string& name) {
  const fs::path dir = scratch() / name;
  fs::remove_all(dir);
  const Result r = kanegen("generate " + source(model) + " -o " + dir.string() + " --quiet --jacobians");
  REQUIRE(r.status == 0);
  return dir;
}

const char* const kJacobianRows[] = {"forcing_jacobian df/dq", "forcing_jacobian df/du", "d(M a)/dq",
                                     "d(C^T lambda)/dq"};

}  // namespace

TEST_CASE("verify --jacobians compares the Jacobian kernels with the numeric path", "[verify][jacobians]") {
  // Closed loop with a prescribed crank: every Jacobian kernel.
  const Result r =
      kanegen("verify " + source("models/slider_crank.json") + " --jacobians --samples 12 --json");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["passed"].get<bool>());
  for (const char* row : kJacobianRows) {
    bool found = false;
    for (const auto& q : j["quantities"]) {
      if (q["quantity"] != row) continue;
      found = true;
      CHECK(q["applicable"].get<bool>());
      CHECK(q["compared"] == 10);  // at the first 10 samples
    }
    INFO(row);
    CHECK(found);
  }
}

TEST_CASE("verify without --jacobians says the Jacobians are not generated", "[verify][jacobians]") {
  const Result r = kanegen("verify " + source("models/simple_pendulum.json") + " --samples 5 --quiet");
  REQUIRE(r.status == 0);
  CHECK(contains(r.out, "not generated (kanegen verify --jacobians checks them)"));
}

TEST_CASE("corruption: a stiffness literal of forcing_jacobian off by 1e-4 fails, naming it",
          "[verify][corruption][jacobians]") {
  const std::string model = "tests/data/models/flex_hub_planar.json";
  const fs::path dir = generate_with_jacobians(model, "jacobian_stiffness");
  scale_literal(dir / "flex_hub_planar.cpp", "void forcing_jacobian", "", 1000.0, 1 + 1e-4);
  const Result r =
      kanegen("verify " + source(model) + " --kernels " + dir.string() + " --samples 20 --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 1);
  CHECK(contains(r.err, "error: forcing_jacobian df/d"));
  CHECK_FALSE(contains(r.err, "error: forcing ["));  // forcing itself is a separate kernel
}

TEST_CASE("corruption: a sign in d(M a)/dq or d(C^T lambda)/dq fails, naming it",
          "[verify][corruption][jacobians]") {
  const std::string model = "models/slider_crank.json";
  const fs::path dir = generate_with_jacobians(model, "jacobian_sign");
  const std::string kernels[] = {"mass_matrix_product_jacobian", "constraint_force_jacobian"};
  const std::string rows[] = {"d(M a)/dq", "d(C^T lambda)/dq"};
  for (int k = 0; k < 2; ++k) {
    const fs::path copy = scratch() / ("jacobian_sign_" + std::to_string(k));
    fs::remove_all(copy);
    fs::copy(dir, copy);
    // The first entry the kernel assigns, negated.
    corrupt(copy / "slider_crank.cpp", "void " + kernels[k], "\\[[0-9]+\\] = ", "$&-1.0*");
    const Result r =
        kanegen("verify " + source(model) + " --kernels " + copy.string() + " --samples 12 --quiet");
    INFO(kernels[k] << "\n" << r.out << r.err);
    CHECK(r.status == 1);
    CHECK(contains(r.err, "error: " + rows[k]));
  }
}
