// SPDX-License-Identifier: GPL-2.0-or-later
// Assumed modes (a flexible body's `assumed_modes`) through `kanegen modes`:
// the Rayleigh-Ritz frequencies of given shapes against their closed forms.
// Sines on a pinned-pinned beam are its exact modes; (x/L)^2 on a
// cantilever gives sqrt(20) sqrt(EI / (rho A L^4)), the first
// Euler-Bernoulli mode shape its exact frequency; an axial parabola
// sqrt(10 E / rho) / L. The shapes are sampled on an internal mesh (Hermite
// in bending, linear axially), so the axial frequency converges as h^2 with
// a known constant, and the bending ones are exact or close to it.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/run_kanegen.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path scratch() {
  static const fs::path dir = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  return dir;
}

std::string source(const std::string& relative) { return std::string(KANEGEN_SOURCE_DIR) + "/" + relative; }

json read_json(const std::string& path) { return json::parse(kanegen_test::slurp(path)); }

/// The angular frequencies (rad/s, ascending) of `kanegen modes MODEL`.
std::vector<double> omegas(const std::string& model) {
  const kanegen_test::Result r =
      kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_CACHE, scratch(), "modes '" + model + "' --quiet");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json result = json::parse(r.out);
  CHECK(result["stable"].get<bool>());
  std::vector<double> out;
  for (const json& mode : result["modes"]) out.push_back(mode["omega_rad_s"].get<double>());
  return out;
}

/// A test model with its first flexible body changed by `edit`, under a new
/// name, without outputs (their nodes depend on the mesh).
std::string variant(const std::string& model, const std::string& suffix,
                    const std::function<void(json&)>& edit) {
  json j = read_json(source("tests/data/models/" + model + ".json"));
  j["name"] = model + "_" + suffix;
  j.erase("outputs");
  edit(j["bodies"][0]["flexible"]);
  const fs::path path = scratch() / (model + "_" + suffix + ".json");
  std::ofstream(path) << j.dump(2);
  return path.string();
}

/// sqrt(EI / (rho A L^4)) and sqrt(E / rho) / L of a model's first (planar) beam.
struct Scales {
  double bending, axial;
};
Scales scales(const std::string& model) {
  const json m = read_json(model);  // kept alive: f refers into it
  const json& f = m["bodies"][0]["flexible"];
  const double E = f["material"]["E"].get<double>(), rho = f["material"]["density"].get<double>();
  const double A = f["section"]["A"].get<double>(), Iz = f["section"]["Iz"].get<double>();
  const double L = f["length"].get<double>();
  return {std::sqrt(E * Iz / (rho * A * std::pow(L, 4))), std::sqrt(E / rho) / L};
}

double rel_error(double value, double reference) { return (value - reference) / reference; }

const double kPi = 3.14159265358979323846;

}  // namespace

TEST_CASE("assumed modes: sines on a pinned-pinned beam give (k pi)^2 sqrt(EI / (rho A L^4)) exactly",
          "[modes][assumed]") {
  const std::string model = source("tests/data/models/assumed_pinned.json");
  const std::vector<double> w = omegas(model);
  REQUIRE(w.size() == 4);
  const Scales s = scales(model);
  for (int k = 1; k <= 3; ++k) {
    const double expected = k * k * kPi * kPi * s.bending;
    INFO("mode " << k << ": " << w[k - 1] << " rad/s, expected " << expected);
    CHECK(std::abs(rel_error(w[k - 1], expected)) < 1e-6);
  }
}

TEST_CASE("assumed modes: an axial parabola gives sqrt(10 E / rho) / L, to the mesh's (h/L)^2 / 3",
          "[modes][assumed]") {
  // For u = 4 s (1 - s), s = x/L, linear interpolation on n elements lowers
  // int u'^2 by the factor 1 - 1/n^2 and int u^2 by 1 - 5/(3 n^2): omega is
  // high by 1/(3 n^2) (3.3e-5 on the default 100 elements).
  const std::string model = source("tests/data/models/assumed_pinned.json");
  const double axial = omegas(model).back();
  const double exact = std::sqrt(10.0) * scales(model).axial;
  const double n = 100;
  INFO("axial: " << axial << " rad/s, Rayleigh-Ritz " << exact << ", error " << rel_error(axial, exact));
  CHECK(std::abs(rel_error(axial, exact)) < 1e-4);
  CHECK(std::abs(rel_error(axial, exact) - 1 / (3 * n * n)) < 0.05 / (3 * n * n));
}

TEST_CASE("assumed modes: the axial frequency converges as h^2 with the internal mesh", "[modes][assumed]") {
  std::vector<double> errors;
  for (int n : {10, 20, 40}) {
    const std::string model = variant("assumed_pinned", "e" + std::to_string(n), [&](json& f) {
      f["elements"] = n;
      f["assumed_modes"] = json::array({{{"u", "4*(x/L)*(1-x/L)"}}});
    });
    const std::vector<double> w = omegas(model);
    REQUIRE(w.size() == 1);
    errors.push_back(rel_error(w[0], std::sqrt(10.0) * scales(model).axial));
    INFO(n << " elements: error " << errors.back() << ", predicted " << 1.0 / (3.0 * n * n));
    CHECK(std::abs(errors.back() - 1.0 / (3.0 * n * n)) < 0.05 / (3.0 * n * n));
  }
  CHECK(errors[0] / errors[1] == Approx(4.0).epsilon(0.02));
  CHECK(errors[1] / errors[2] == Approx(4.0).epsilon(0.02));
}

TEST_CASE("assumed modes: the bending frequencies converge as h^4 with the internal mesh",
          "[modes][assumed]") {
  // sin(3 pi x / L) on 4, 8, 16 elements: the Hermite interpolant's error in
  // the Rayleigh quotient falls by about 16 per halving.
  std::vector<double> errors;
  for (int n : {4, 8, 16}) {
    const std::string model = variant("assumed_pinned", "b" + std::to_string(n), [&](json& f) {
      f["elements"] = n;
      f["assumed_modes"] = json::array({{{"v", "sin(3*pi*x/L)"}}});
    });
    const std::vector<double> w = omegas(model);
    REQUIRE(w.size() == 1);
    errors.push_back(rel_error(w[0], 9 * kPi * kPi * scales(model).bending));
    INFO(n << " elements: error " << errors.back());
  }
  INFO("errors " << errors[0] << ", " << errors[1] << ", " << errors[2]);
  CHECK(std::abs(errors[2]) < 1e-4);
  CHECK(std::abs(errors[0] / errors[1]) > 12);
  CHECK(std::abs(errors[1] / errors[2]) > 12);
}

TEST_CASE(
    "assumed modes: (x/L)^2 on a cantilever gives the Rayleigh quotient sqrt(20) sqrt(EI / (rho A L^4))",
    "[modes][assumed]") {
  const std::string model = source("tests/data/models/assumed_cantilever.json");
  const std::vector<double> w = omegas(model);
  REQUIRE(w.size() == 1);
  const double expected = std::sqrt(20.0) * scales(model).bending;
  INFO(w[0] << " rad/s, expected " << expected);
  CHECK(std::abs(rel_error(w[0], expected)) < 1e-7);  // the mesh holds a parabola exactly
}

TEST_CASE("assumed modes: the first Euler-Bernoulli mode shape of a cantilever gives its frequency",
          "[modes][assumed]") {
  // phi = cosh(y) - cos(y) - sigma (sinh(y) - sin(y)), y = b x, b L = 1.875104,
  // sigma = 0.7340955, written with exp (the expressions have no cosh):
  // (1 - sigma)/2 e^y + (1 + sigma)/2 e^-y - cos(y) + sigma sin(y). Then
  // omega = (b L)^2 sqrt(EI / (rho A L^4)), and a second shape (x/L)^3 does
  // not lower it (the exact mode is in the span).
  const std::string model = variant("assumed_cantilever", "euler_bernoulli", [](json& f) {
    const std::string y = "(1.875104*x/L)";
    f["assumed_modes"] = json::array(
        {{{"v", "0.13295225*exp" + y + " + 0.86704775*exp(-" + y + ") - cos" + y + " + 0.7340955*sin" + y}},
         {{"v", "(x/L)^3"}}});
  });
  const std::vector<double> w = omegas(model);
  REQUIRE(w.size() == 2);
  const double expected = 1.875104 * 1.875104 * scales(model).bending;
  INFO(w[0] << " rad/s, expected " << expected);
  CHECK(std::abs(rel_error(w[0], expected)) < 1e-5);
}
