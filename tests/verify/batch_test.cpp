// SPDX-License-Identifier: GPL-2.0-or-later
// The runner's `batch` command (what kanegen verify talks to), in-process
// on the generated simple pendulum: the kernels named on each line, called
// through their spec, parameters per line, and bad lines.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <kanegen/runtime/driver.hpp>
#include <kanegen/runtime/kernel_thunks.hpp>
#include <kanegen/runtime/model.hpp>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "simple_pendulum.hpp"

namespace {

using nlohmann::json;

struct Outcome {
  int code;
  std::vector<json> replies;
  std::string err;
};

std::string read_all(std::FILE* f) {
  std::string s;
  std::rewind(f);
  char buf[4096];
  for (size_t got; (got = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, got);
  std::fclose(f);
  return s;
}

Outcome batch(const std::string& input, std::vector<std::string> extra = {}) {
  std::FILE* in = std::tmpfile();
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  REQUIRE((in && out && err));
  std::fputs(input.c_str(), in);
  std::rewind(in);
  std::vector<std::string> args{"simple_pendulum_runner", "batch"};
  args.insert(args.end(), extra.begin(), extra.end());
  const int code = kanegen::runtime::run_model<kanegen_models::simple_pendulum::System>(args, in, out, err);
  std::fclose(in);
  Outcome o{code, {}, read_all(err)};
  std::istringstream lines(read_all(out));
  for (std::string line; std::getline(lines, line);) o.replies.push_back(json::parse(line));
  return o;
}

}  // namespace

TEST_CASE("batch answers each line with the kernels it names, at the line's parameters", "[batch]") {
  // The simple pendulum: M = m l^2, V = -m g l cos q.
  const double q = 0.3, m = 1.5, l = 0.8, g = 9.0;
  const Outcome o = batch(
      "{\"t\": 0, \"q\": [0.3], \"u\": [-1.2], \"tau\": [0.5], \"p\": [1.5, 0.8, 9.0], \"kernels\": "
      "[\"mass_matrix\", \"potential_energy\", \"outputs\"]}\n"
      "{\"q\": [0.3], \"u\": [-1.2], \"kernels\": [\"mass_matrix\"]}\n");
  REQUIRE(o.code == 0);
  REQUIRE(o.replies.size() == 2);
  REQUIRE(o.replies[0].size() == 1);  // only "kernels"
  const json& a = o.replies[0]["kernels"];
  CHECK(a.size() == 3);
  CHECK(a["mass_matrix"]["M"][0][0].get<double>() == Approx(m * l * l));
  CHECK(a["potential_energy"]["returns"].get<double>() == Approx(-m * g * l * std::cos(q)));
  CHECK(a["outputs"]["y"].size() == 4);
  // Without "p" the line uses the defaults again (m = 1, l = 1, g = 9.81), not the previous line's values.
  CHECK(o.replies[1]["kernels"]["mass_matrix"]["M"][0][0].get<double>() == Approx(1.0));
}

TEST_CASE("batch gives gravity, nonconservative_power and inverse_dynamics; controller needs the kernels",
          "[batch]") {
  const double q = 0.3, u = -1.2, tau = 0.5, m = 1.5, l = 0.8, g = 9.0, a = 2.0;
  const Outcome o = batch(
      "{\"q\": [0.3], \"u\": [-1.2], \"tau\": [0.5], \"p\": [1.5, 0.8, 9.0], \"kernels\": [\"gravity\", "
      "\"nonconservative_power\", \"inverse_dynamics\"], \"input_udot\": [2.0]}\n"
      "{\"q\": [0.3], \"u\": [-1.2], \"kernels\": [\"linearize\"]}\n");
  REQUIRE(o.replies.size() == 2);
  const json& r = o.replies[0]["kernels"];
  CHECK(r["gravity"]["g"][0].get<double>() == Approx(m * g * l * std::sin(q)));
  CHECK(r["nonconservative_power"]["returns"].get<double>() == Approx(tau * u));
  // M a - f with the inputs 0: the torque that gives the acceleration a.
  CHECK(r["inverse_dynamics"]["tau"][0].get<double>() == Approx(m * l * l * a + m * g * l * std::sin(q)));
  CHECK(o.replies[1]["error"] ==
        "\"kernels\": the model has no linearize kernel; generate the model with --controller");
  CHECK(o.code == 1);
}

TEST_CASE("batch calls the kernels named in \"kernels\" through their spec", "[batch]") {
  // The simple pendulum: M = m l^2, f = -m g l sin q + tau, T = m l^2 u^2 / 2.
  const double q = 0.3, u = -1.2, tau = 0.5, m = 1.5, l = 0.8, g = 9.0, a = 2.0;
  const Outcome o = batch(
      "{\"q\": [0.3], \"u\": [-1.2], \"tau\": [0.5], \"p\": [1.5, 0.8, 9.0], "
      "\"kernels\": [\"mass_matrix\", \"forcing\", \"kinetic_energy\", \"forward_dynamics\", "
      "\"inverse_dynamics\"], \"input_udot\": [2.0]}\n");
  REQUIRE(o.code == 0);
  REQUIRE(o.replies.size() == 1);
  const json& k = o.replies[0]["kernels"];
  CHECK(k.size() == 5);
  CHECK(k["mass_matrix"]["M"][0][0].get<double>() == Approx(m * l * l));  // NU*NU: rows of NU
  CHECK(k["forcing"]["f"][0].get<double>() == Approx(-m * g * l * std::sin(q) + tau));
  CHECK(k["kinetic_energy"]["returns"].get<double>() == Approx(0.5 * m * l * l * u * u));
  CHECK(k["forward_dynamics"]["udot"][0].get<double>() ==
        Approx((-m * g * l * std::sin(q) + tau) / (m * l * l)));
  CHECK(k["forward_dynamics"]["returns"].get<double>() == 0.0);
  CHECK(k["inverse_dynamics"]["tau"][0].get<double>() == Approx(m * l * l * a + m * g * l * std::sin(q)));
  CHECK_FALSE(k["mass_matrix"].contains("returns"));  // void
}

TEST_CASE("batch \"kernels\" calls every kernel of the spec the model has, by its spec alone", "[batch]") {
  // Nothing here names a kernel: a kernel added to kernels.def is covered too.
  const kanegen::runtime::Model model =
      kanegen::runtime::make_model<kanegen_models::simple_pendulum::System>();
  std::string names;
  std::vector<const kanegen::runtime::KernelSpec*> called;
  for (const kanegen::runtime::KernelSpec& spec : kanegen::runtime::kernel_specs) {
    bool arrays_and_scalars = spec.params != kanegen::runtime::ParamsAccess::write;
    for (std::size_t i = 0; i < spec.argument_count; ++i)
      arrays_and_scalars =
          arrays_and_scalars && (spec.arguments[i].role != kanegen::runtime::ArgumentRole::text &&
                                 spec.arguments[i].role != kanegen::runtime::ArgumentRole::index);
    if (!arrays_and_scalars || !model.has(spec.kernel)) continue;
    names += std::string(names.empty() ? "" : ", ") + "\"" + spec.name + "\"";
    called.push_back(&spec);
  }
  REQUIRE(called.size() >= 10);
  const Outcome o = batch("{\"q\": [0.3], \"u\": [1], \"kernels\": [" + names +
                          "], \"input_udot\": [0.5], \"input_a\": [1], \"input_lambda\": []}\n");
  REQUIRE(o.code == 0);
  const json& k = o.replies.at(0)["kernels"];
  CHECK(k.size() == called.size());
  for (const kanegen::runtime::KernelSpec* spec : called) {
    INFO(spec->name);
    REQUIRE(k.contains(spec->name));
    for (std::size_t i = 0; i < spec->argument_count; ++i)
      if (spec->arguments[i].role == kanegen::runtime::ArgumentRole::out) {
        const int n = kanegen::runtime::kernel_argument_length(model.table(), spec->arguments[i].size);
        CHECK(k[spec->name][spec->arguments[i].name].flatten().size() == static_cast<std::size_t>(n));
      }
    CHECK(k[spec->name].contains("returns") == (std::string(spec->returns) != "void"));
  }
}

TEST_CASE("batch skips blank lines", "[batch]") {
  const Outcome o = batch(
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forward_dynamics\"]}\n\n"
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"kinetic_energy\"]}\n");
  REQUIRE(o.code == 0);
  REQUIRE(o.replies.size() == 2);
  CHECK(o.replies[0]["kernels"].contains("forward_dynamics"));
  CHECK(o.replies[1]["kernels"]["kinetic_energy"]["returns"].get<double>() == Approx(0.5));
}

TEST_CASE("batch: a bad line gives an error answer, the others are still answered", "[batch]") {
  const char* bad[] = {
      "{\"q\": [0.3], \"kernels\": [\"forcing\"]}",                        // u missing
      "{\"q\": [0.3, 1], \"u\": [1], \"kernels\": [\"forcing\"]}",         // wrong count
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing\"], \"x\": 1}",  // unknown key
      "{\"q\": [0.3], \"u\": [nan], \"kernels\": [\"forcing\"]}",          // not a number
      "[1, 2]",                                                            // not an object
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing\"]} trailing",
      "{\"q\": [0.3], \"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing\"]}",  // duplicate key
      // no kernels named; the fields before "kernels" are gone
      "{\"q\": [0.3], \"u\": [1]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": []}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing\"], \"eval\": \"udot\"}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing\"], \"jacobians\": true}",
      // kernels: an unknown name, one the model lacks, a missing or short input, not names
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"mass_matrixx\"]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"linearize\"]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing_jacobian\"]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"inverse_dynamics\"]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"inverse_dynamics\"], \"input_udot\": []}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [1]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": [\"forcing\", \"forcing\"]}",
      "{\"q\": [0.3], \"u\": [1], \"kernels\": \"forcing\"}",
  };
  for (const char* line : bad) {
    INFO(line);
    const Outcome o =
        batch(std::string(line) + "\n{\"q\": [0], \"u\": [0], \"kernels\": [\"forward_dynamics\"]}\n");
    CHECK(o.code == 1);
    REQUIRE(o.replies.size() == 2);
    REQUIRE(o.replies[0].contains("error"));
    if (std::string(line).find("eval") != std::string::npos ||
        std::string(line).find("jacobians") != std::string::npos)
      CHECK(o.replies[0]["error"].get<std::string>().rfind("unknown key", 0) == 0);  // an old field is named
    CHECK(o.replies[1]["kernels"]["forward_dynamics"]["udot"][0].get<double>() == 0.0);
  }
}

TEST_CASE("batch --help describes the protocol, unknown options are usage errors", "[batch]") {
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  const int code = kanegen::runtime::run_model<kanegen_models::simple_pendulum::System>(
      {"runner", "batch", "--help"}, out, err);
  CHECK(code == 0);
  const std::string help = read_all(out);
  read_all(err);
  CHECK(help.find("\"kernels\": [\"<kernel>\", ...]") != std::string::npos);
  CHECK(help.find("input_<argument>") != std::string::npos);
  CHECK(batch("", {"--frobnicate"}).code == 2);
}
