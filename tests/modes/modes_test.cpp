// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen modes as a user runs it, on the shipped flexible models: the
// cantilever against Euler-Bernoulli (and its convergence with the mesh),
// the static tip deflection from the linearisation (checked by `eval`), the
// rotating cantilever against the rotating-beam table, the L-frame against
// CalculiX, a beam with a tip mass against its frequency equation, a
// pendulum (a rigid model), closed loops (a propped bar against Euler-Bernoulli,
// the solid slider-crank's rod against CalculiX), and the failures: an
// unstable equilibrium, a singular mass matrix, loops that leave no motion,
// bad options.
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_kanegen.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using kanegen_test::Result;
using kanegen_test::slurp;

fs::path scratch() {
  static const fs::path dir = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  return dir;
}

std::string source(const std::string& relative) { return std::string(KANEGEN_SOURCE_DIR) + "/" + relative; }

/// Runs kanegen (arguments in shell syntax) with a private runner cache.
Result kanegen(const std::string& args) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_CACHE, scratch(), args);
}

/// `kanegen modes MODEL ARGS --quiet`, which must succeed.
json modes(const std::string& model, const std::string& args = "") {
  const Result r = kanegen("modes '" + model + "' --quiet " + args);
  INFO(r.err);
  REQUIRE(r.status == 0);
  return json::parse(r.out);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

double rel_error(double value, double reference) { return (value - reference) / reference; }

json read_json(const std::string& path) { return json::parse(slurp(path)); }

/// A copy of a shipped model under another name with `elements` elements
/// (one straight beam), in the scratch directory.
std::string variant(const std::string& model, int elements) {
  json j = read_json(source("models/" + model + ".json"));
  j["name"] = model + "_" + std::to_string(elements);
  j["bodies"][0]["flexible"]["elements"] = elements;
  const fs::path path = scratch() / (model + "_" + std::to_string(elements) + ".json");
  std::ofstream(path) << j.dump(2);
  return path.string();
}

/// The modes whose shapes are bending: less than 1 % of the shape in the
/// axial (".u") coordinates. Axial and bending motion are uncoupled on a
/// straight planar beam; about a bent equilibrium (a beam sagging in
/// gravity, with the nonlinear axial strain of geometric stiffening) they
/// couple at the order of the slopes.
std::vector<double> bending_omegas(const json& result) {
  std::vector<double> omegas;
  for (const json& mode : result["modes"]) {
    double axial = 0, total = 0;
    for (const auto& [name, value] : mode["shape"].items()) {
      const double v = value.get<double>();
      total += v * v;
      if (name.size() > 2 && name.compare(name.size() - 2, 2, ".u") == 0) axial += v * v;
    }
    if (axial < 1e-2 * total) omegas.push_back(mode["omega_rad_s"].get<double>());
  }
  return omegas;
}

/// sqrt(rho A L^4 / (E Iz)) of a model's straight planar beam.
double time_scale(const json& model) {
  const json& f = model["bodies"][0]["flexible"];
  const double rho_a = f["material"]["density"].get<double>() * f["section"]["A"].get<double>();
  const double ei = f["material"]["E"].get<double>() * f["section"]["Iz"].get<double>();
  return std::sqrt(rho_a * std::pow(f["length"].get<double>(), 4) / ei);
}

std::vector<std::string> coordinate_names(const json& result) {
  return result["coordinates"].get<std::vector<std::string>>();
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  FAIL("no coordinate " << name);
  return -1;
}

std::string csv(const Eigen::VectorXd& x) {
  std::ostringstream s;
  s.precision(17);
  for (Eigen::Index i = 0; i < x.size(); ++i) s << (i ? "," : "") << x[i];
  return s.str();
}

constexpr double kBetaL[] = {1.875104, 4.694091, 7.854757};

/// The rotating cantilever's flapwise omega sqrt(rho A L^4 / (E I)) at
/// lambda = Omega sqrt(rho A L^4 / (E I)) (formulation.md, reference values).
struct RotatingBeamRow {
  double lambda, omega[3];
};
constexpr RotatingBeamRow kRotatingBeamTable[] = {{0, {3.5160, 22.0345, 61.6973}},
                                                  {2, {4.1373, 22.6149, 62.2732}},
                                                  {4, {5.5850, 24.2734, 63.9668}},
                                                  {10, {11.2023, 33.6404, 74.6494}}};

/// The cantilever's first three bending frequencies over the Euler-Bernoulli
/// ones, minus 1: unloaded (P = 0), as Euler-Bernoulli's beam is.
std::vector<double> cantilever_errors(const std::string& model) {
  const json result = modes(model, "--set P=0");
  CHECK(result["stable"].get<bool>());
  const std::vector<double> omega = bending_omegas(result);
  REQUIRE(omega.size() >= 3);
  const double t = time_scale(read_json(model));
  std::vector<double> errors;
  for (int k = 0; k < 3; ++k) {
    errors.push_back(rel_error(omega[k] * t, kBetaL[k] * kBetaL[k]));
    INFO(model << " mode " << k + 1 << ": " << omega[k] << " rad/s, error " << errors.back());
  }
  return errors;
}

}  // namespace

TEST_CASE("cantilever: first three bending frequencies within 0.1 % of Euler-Bernoulli", "[modes]") {
  const std::vector<double> e = cantilever_errors(source("models/cantilever.json"));
  for (int k = 0; k < 3; ++k) {
    INFO("mode " << k + 1 << " error " << e[k]);
    CHECK(std::abs(e[k]) < 1e-3);
  }
}

TEST_CASE("cantilever: the frequencies converge from above with 5, 10, 20 elements", "[modes]") {
  const std::vector<double> e5 = cantilever_errors(variant("cantilever", 5));
  const std::vector<double> e10 = cantilever_errors(variant("cantilever", 10));
  const std::vector<double> e20 = cantilever_errors(variant("cantilever", 20));
  for (int k = 0; k < 3; ++k) {
    INFO("mode " << k + 1 << ": errors " << e5[k] << ", " << e10[k] << ", " << e20[k]);
    CHECK(e5[k] > e10[k]);
    CHECK(e10[k] > e20[k]);
    CHECK(e20[k] > -1e-7);  // from above (a conforming mesh), to the table's rounding
  }
}

TEST_CASE("cantilever: modes finds the static tip deflection P L^3 / (3 E I), and eval the equilibrium there",
          "[modes]") {
  // The beam's geometric stiffening is its nonlinear axial strain, so modes
  // linearises about the loaded equilibrium, which it finds by Newton's
  // method on the same K and r and reports.
  const std::string model = source("models/cantilever.json");
  const json result = modes(model, "--matrices --count 1");
  REQUIRE(result.contains("equilibrium"));
  const std::vector<std::string> coordinates = coordinate_names(result);
  Eigen::VectorXd x(static_cast<Eigen::Index>(coordinates.size()));
  for (std::size_t i = 0; i < coordinates.size(); ++i)
    x[static_cast<Eigen::Index>(i)] = result["equilibrium"]["q"][coordinates[i]].get<double>();

  const json m = read_json(model);
  const json& f = m["bodies"][0]["flexible"];
  const double P = m["parameters"]["P"].get<double>(), L = f["length"].get<double>();
  const double EI = f["material"]["E"].get<double>() * f["section"]["Iz"].get<double>();
  const double v = x[index_of(coordinates, "beam.n10.v")],
               theta = x[index_of(coordinates, "beam.n10.theta_z")];
  INFO("tip deflection " << v << " m, rotation " << theta);
  CHECK(std::abs(rel_error(v, -P * L * L * L / (3 * EI))) < 1e-6);
  CHECK(std::abs(rel_error(theta, -P * L * L / (2 * EI))) < 1e-6);

  // The compiled forcing vanishes at that state (to the load's round-off).
  const Result e =
      kanegen("eval '" + model + "' --quiet --q " + csv(x) + " --u " + csv(Eigen::VectorXd::Zero(x.size())));
  INFO(e.err);
  REQUIRE(e.status == 0);
  double largest = 0;
  const json answer = json::parse(e.out);  // kept alive: a range-for over a temporary's member dangles
  for (const json& fi : answer["forcing"]) largest = std::max(largest, std::abs(fi.get<double>()));
  CHECK(largest < 1e-8 * P);
}

TEST_CASE("spinning beam: flapwise frequencies at lambda = 0, 2, 4, 10 within 0.5 % of the table",
          "[modes]") {
  const std::string model = source("models/spinning_beam.json");
  const double t = time_scale(read_json(model));
  for (const RotatingBeamRow& row : kRotatingBeamTable) {
    const double spin = row.lambda / t;
    std::ostringstream set;
    set.precision(17);
    set << "--set Omega=" << spin;
    const json result = modes(model, set.str());
    CHECK(result["stable"].get<bool>());
    REQUIRE(result["prescribed"].size() == 1);
    CHECK(result["prescribed"][0]["joint"] == "hub");
    CHECK(result["prescribed"][0]["u"].get<double>() == Approx(spin).epsilon(1e-12));
    CHECK(result["coordinates"][0] != "hub");  // the hub is not an eigen-coordinate
    const std::vector<double> omega = bending_omegas(result);
    REQUIRE(omega.size() >= 3);
    for (int k = 0; k < 3; ++k) {
      const double e = rel_error(omega[k] * t, row.omega[k]);
      INFO("lambda " << row.lambda << " mode " << k + 1 << ": " << omega[k] * t << " against " << row.omega[k]
                     << ", error " << e);
      CHECK(std::abs(e) < 5e-3);
    }
  }
}

TEST_CASE("spinning CPS8 strip: flapwise frequencies rise with spin as the rotating-beam table says",
          "[modes][mesh_stiffening]") {
  // spinning_beam.json's strip as a mesh body, stiffened by its second-order
  // displacement field (issue 18); without it the frequencies stay at rest.
  const std::string model = source("tests/data/models/spinning_cps8.json");
  json linear_model = read_json(model);
  linear_model["name"] = "spinning_cps8_linear";
  linear_model["bodies"][0]["flexible"]["geometric_stiffening"] = false;
  linear_model["bodies"][0]["flexible"]["mesh"]["file"] = source("tests/data/models/free_strip_cps8.inp");
  const fs::path linear = scratch() / "spinning_cps8_linear.json";
  std::ofstream(linear) << linear_model.dump(2);
  const double t = std::sqrt(2700 * 1e-4 / (7e10 * 1.3333333333333333e-10));  // sqrt(rho A L^4 / (E I))
  double rest = 0;
  for (const RotatingBeamRow& row : kRotatingBeamTable) {
    std::ostringstream set;
    set.precision(17);
    set << "--set Omega=" << row.lambda / t;
    const json result = modes(model, set.str());
    CHECK(result["stable"].get<bool>());
    REQUIRE(result["modes"].size() >= 3);
    for (int k = 0; k < 3; ++k) {
      const double omega = result["modes"][k]["omega_rad_s"].get<double>() * t;
      const double e = rel_error(omega, row.omega[k]);
      INFO("lambda " << row.lambda << " mode " << k + 1 << ": " << omega << " against " << row.omega[k]
                     << ", error " << e);
      // The strip is 0.3 %, 0.6 % and 1.0 % above Euler-Bernoulli at rest (plane stress, its clamped root).
      CHECK(std::abs(e) < 1.5e-2);
      if (k == 0 && row.lambda == 0) rest = omega;
      // The first mode's rise, relative to the strip's own rest frequency, is the table's.
      if (k == 0) CHECK(omega / rest == Approx(row.omega[0] / kRotatingBeamTable[0].omega[0]).epsilon(3e-3));
    }
    if (row.lambda == 10) {
      const double unstiffened =
          modes(linear.string(), set.str())["modes"][0]["omega_rad_s"].get<double>() * t;
      INFO("without stiffening at lambda 10: " << unstiffened);
      CHECK(unstiffened == Approx(rest).epsilon(1e-2));
    }
  }
}

TEST_CASE("Euler's column: the first frequency goes to zero at the critical load, nodal and modal",
          "[modes][stiffening]") {
  // A clamped-free column pushed at its tip: the applied node force enters
  // the geometric stiffness (the nonlinear axial strain of the nodal beam,
  // the foreshortening of the modal one). Euler: P_cr = pi^2 EI / (4 L^2).
  const double pi = 3.14159265358979323846, EI = 2.1e11 * 2.5e-9, p_cr = pi * pi * EI / 4.0;
  for (const char* name : {"euler_column", "euler_column_modal"}) {
    const std::string model = source(std::string("tests/data/models/") + name + ".json");
    const auto omega2 = [&](double fraction) {
      std::ostringstream set;
      set.precision(17);
      set << "--count 1 --set P=" << fraction * p_cr;
      const json result = modes(model, set.str());
      return result["modes"][0]["eigenvalue"].get<double>();
    };
    const double free = omega2(0.0), half = omega2(0.5), near = omega2(0.99), nearer = omega2(0.999);
    // omega^2 falls about as 1 - P / P_cr (Galef's approximation for a cantilever) ...
    INFO(name << ": omega^2 = " << free << ", " << half << ", " << near << ", " << nearer
              << " 1/s^2 at P / P_cr = 0, 0.5, 0.99, 0.999");
    CHECK(std::abs(half / free - 0.5) < 0.02);
    CHECK(near / free < 0.015);
    // ... and reaches zero at Euler's load: extrapolated from 0.99 and 0.999 P_cr.
    const double zero = 0.99 + (0.999 - 0.99) * near / (near - nearer);
    INFO("omega^2 extrapolates to zero at " << zero << " P_cr");
    CHECK(std::abs(zero - 1.0) < 1e-3);
    // Past it, the straight column is unstable.
    std::ostringstream past;
    past.precision(17);
    past << "modes '" << model << "' --quiet --set P=" << 1.01 * p_cr;
    const Result r = kanegen(past.str());
    CHECK(r.status == 1);
    CHECK(contains(r.err, "unstable"));
    WARN(name << ": omega_1^2 / omega_1^2(P = 0) = " << half / free << " at P_cr / 2, " << near / free
              << " at 0.99 P_cr; zero extrapolated at " << zero << " P_cr");
  }
}

TEST_CASE("L-frame: natural frequencies within 1 % of CalculiX", "[modes]") {
  std::ifstream in(source("tests/fem/data/l_frame_ccx.txt"));
  REQUIRE(in.good());
  std::vector<double> reference;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    int mode;
    double omega;
    words >> mode >> omega;
    reference.push_back(omega);
  }
  REQUIRE(reference.size() == 12);
  const json result = modes(source("models/l_frame.json"), "--count 12");
  REQUIRE(result["modes"].size() == 12);
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const double omega = result["modes"][k]["omega_rad_s"].get<double>();
    INFO("mode " << k + 1 << ": kanegen " << omega << " rad/s, CalculiX " << reference[k]);
    CHECK(std::abs(rel_error(omega, reference[k])) < 1e-2);
  }
}

namespace {

/// The lowest root above `from` of the frequency equation of a clamped beam
/// with a tip mass (mu = M / (rho A L)) and rotary inertia (j = J / (rho A L^3)):
/// det of the boundary conditions W(0) = W'(0) = 0, EI W''(L) = J w^2 W'(L),
/// EI W'''(L) = -M w^2 W(L), in x = beta L.
double tip_mass_root(double mu, double j, double from) {
  const auto det = [&](double x) {
    const double c = std::cos(x), s = std::sin(x), ch = std::cosh(x), sh = std::sinh(x);
    Eigen::Matrix4d a;
    a << 1, 0, 1, 0,  //
        0, 1, 0, 1,   //
        -c + j * x * x * x * s, -s - j * x * x * x * c, ch - j * x * x * x * sh, sh - j * x * x * x * ch,
        s + mu * x * c, -c + mu * x * s, sh + mu * x * ch, ch + mu * x * sh;
    return a.determinant();
  };
  double lo = from, hi = from + 0.01;
  while (det(lo) * det(hi) > 0) {
    lo = hi;
    hi += 0.01;
  }
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (det(lo) * det(mid) <= 0 ? hi : lo) = mid;
  }
  return (lo + hi) / 2;
}

}  // namespace

TEST_CASE("beam with a tip mass: held hub against the frequency equation, and the hub freed", "[modes]") {
  const std::string model = source("models/beam_tip_mass.json");
  const json m = read_json(model);
  const json& f = m["bodies"][1]["flexible"];
  const double rho_a = f["material"]["density"].get<double>() * f["section"]["A"].get<double>();
  const double L = f["length"].get<double>();
  const double mu = f["tip"]["mass"].get<double>() / (rho_a * L);
  const double j = f["tip"]["inertia"]["izz"].get<double>() / (rho_a * L * L * L);
  const double t = std::sqrt(rho_a * std::pow(L, 4) /
                             (f["material"]["E"].get<double>() * f["section"]["Iz"].get<double>()));

  const json held = modes(model);
  CHECK(held["held"] == json::array({"shoulder"}));
  const std::vector<double> omega = bending_omegas(held);
  REQUIRE(omega.size() >= 2);
  double from = 0.5;
  for (int k = 0; k < 2; ++k) {
    const double x = tip_mass_root(mu, j, from);
    from = x + 0.01;
    const double e = rel_error(omega[k] * t, x * x);
    INFO("mode " << k + 1 << ": " << omega[k] << " rad/s, beta L = " << x << ", error " << e);
    CHECK(std::abs(e) < 1e-3);
  }

  const json free = modes(model, "--free-joints --count 3");
  CHECK(free["stable"].get<bool>());
  CHECK(free["held"].empty());
  CHECK(free["coordinates"][0] == "shoulder");
  CHECK(free["modes"][0]["omega_rad_s"].get<double>() == 0.0);  // the arm turning as a whole
  CHECK(free["modes"][0]["shape"]["shoulder"].get<double>() > 0.0);
  // Freeing the hub lowers the stiffness seen by every mode (Rayleigh), so the first elastic
  // mode of the free arm lies above the held one's, below its second (interlacing).
  const double first_free = free["modes"][1]["omega_rad_s"].get<double>();
  CHECK(first_free > omega[0]);
  CHECK(first_free < omega[1]);
}

TEST_CASE("rigid model: a pendulum's frequency, and an upright one is unstable", "[modes]") {
  const std::string model = source("models/simple_pendulum.json");
  const json hanging = modes(model, "--q0 pivot=0");
  CHECK(hanging["coordinates"] == json::array({"pivot"}));
  REQUIRE(hanging["modes"].size() == 1);
  CHECK(hanging["modes"][0]["omega_rad_s"].get<double>() == Approx(std::sqrt(9.81)).epsilon(1e-7));
  CHECK(hanging["modes"][0]["frequency_hz"].get<double>() ==
        Approx(std::sqrt(9.81) / (2 * M_PI)).epsilon(1e-7));
  CHECK(hanging["modes"][0]["shape"]["pivot"].get<double>() == Approx(1.0).epsilon(1e-9));  // m l^2 = 1

  const json longer = modes(model, "--q0 pivot=0 --set l=4");
  CHECK(longer["modes"][0]["omega_rad_s"].get<double>() == Approx(std::sqrt(9.81 / 4)).epsilon(1e-7));

  const Result upright = kanegen("modes '" + model + "' --quiet --q0 pivot=3.141592653589793");
  CHECK(upright.status == 1);
  CHECK(contains(upright.err, "unstable"));
  CHECK(contains(upright.err, "mode 1"));
  const json j = json::parse(upright.out);
  CHECK_FALSE(j["stable"].get<bool>());
  CHECK_FALSE(j["modes"][0]["stable"].get<bool>());
  CHECK(j["modes"][0]["omega_rad_s"].get<double>() == 0.0);
  CHECK(j["modes"][0]["growth_rate"].get<double>() == Approx(std::sqrt(9.81)).epsilon(1e-6));
}

TEST_CASE("loops: a bar pinned at its tip by a loop has the clamped-pinned frequencies of Euler-Bernoulli",
          "[modes][loops]") {
  // tests/data/models/slender_propped.json: the slender CPS8 bar (0.4 x 0.01 x 0.002 m steel) clamped at
  // its root, its tip edge pinned to the ground by a planar revolute loop (Craig-Bampton on TIP). The
  // modes live on the loop's tangent space: beta L = 3.926602, 7.068583 (the clamped-free bar has
  // 1.875104: without the loop the first mode would be 4.4 times lower).
  const json r = modes(source("tests/data/models/slender_propped.json"));
  const double E = 2.1e11, t = 0.002, h = 0.01, L = 0.4, rho = 7800;
  const double scale = std::sqrt(E * t * h * h * h / 12 / (rho * t * h * std::pow(L, 4)));
  REQUIRE(r["modes"].size() == 3);  // 5 coordinates, 2 loop equations
  CHECK(r["loop_forces"].size() == 2);
  // Shear and rotary inertia, which the beam leaves out, lower the bar's (measured -0.14 %, -0.24 %).
  CHECK(rel_error(r["modes"][0]["omega_rad_s"], std::pow(3.926602, 2) * scale) == Approx(0).margin(5e-3));
  CHECK(rel_error(r["modes"][1]["omega_rad_s"], std::pow(7.068583, 2) * scale) == Approx(0).margin(5e-3));
}

TEST_CASE(
    "loops: the solid slider-crank's rod keeps CalculiX's clamped-free frequencies across the plane only",
    "[modes][loops]") {
  // models/solid_slider_crank.json, its rod angle and slider held, the crank turning: the planar loop holds
  // the small end in the plane of motion, not across it. Across it the rod is the clamped-free rod of
  // tests/fem/data/solid_slider_crank_ccx.txt (CalculiX: 450.250, 2825.37, 7909.09 rad/s; the spin adds
  // little); in it the first mode (459.095 rad/s free) is pinned away.
  const json r = modes(source("models/solid_slider_crank.json"));
  std::vector<double> omega;
  for (const json& m : r["modes"]) omega.push_back(m["omega_rad_s"]);
  REQUIRE(omega.size() == 17 - 3 - 2);  // the elastic coordinates less the loop's 2 equations
  CHECK(rel_error(omega[0], 450.250) == Approx(0).margin(1e-3));
  for (double ccx : {2825.37, 7909.09}) {
    INFO("CalculiX " << ccx);
    CHECK(std::any_of(omega.begin(), omega.end(), [&](double w) { return std::abs(w / ccx - 1) < 1e-3; }));
  }
  // Without the loop a second mode would be near 459 rad/s (453 with the rod's spin softening).
  CHECK(std::count_if(omega.begin(), omega.end(), [](double w) { return w < 1000; }) == 1);
  CHECK(omega[1] > 2000);
}

TEST_CASE("loops: a mechanism whose loops leave the eigen-coordinates no motion is an error",
          "[modes][loops]") {
  // The rigid slider-crank: its crank prescribed, the rod angle and the slider follow it.
  const Result r = kanegen("modes '" + source("models/slider_crank.json") + "' --quiet");
  CHECK(r.status == 1);
  CHECK(contains(r.err, "no motion"));
  CHECK(r.out.empty());
}

TEST_CASE("failures: a singular mass matrix, unknown names, a prescribed joint's state", "[modes]") {
  const Result singular = kanegen("modes '" + source("models/simple_pendulum.json") + "' --quiet --set m=0");
  CHECK(singular.status == 1);
  CHECK(contains(singular.err, "error: "));
  CHECK(contains(singular.err, "singular"));
  CHECK(contains(singular.err, "'pivot'"));
  CHECK(singular.out.empty());

  const Result unknown =
      kanegen("modes '" + source("models/simple_pendulum.json") + "' --quiet --set mass=2");
  CHECK(unknown.status == 1);
  CHECK(contains(unknown.err, "unknown parameter 'mass'; parameters: m, l, g"));

  const Result coordinate =
      kanegen("modes '" + source("models/simple_pendulum.json") + "' --quiet --q0 hinge=0");
  CHECK(coordinate.status == 1);
  CHECK(contains(coordinate.err, "unknown coordinate 'hinge'"));

  const Result prescribed =
      kanegen("modes '" + source("models/spinning_beam.json") + "' --quiet --u0 hub_dot=3");
  CHECK(prescribed.status == 1);
  CHECK(contains(prescribed.err, "prescribed"));

  const Result count = kanegen("modes '" + source("models/simple_pendulum.json") + "' --count 0");
  CHECK(count.status != 0);
}

TEST_CASE("modes --help describes the eigenproblem", "[modes]") {
  const Result r = kanegen("modes --help");
  CHECK(r.status == 0);
  for (const char* part :
       {"--free-joints", "--count", "--set", "--matrices", "prescribed", "docs/modes.md"}) {
    INFO(part);
    CHECK(contains(r.out, part));
  }
}
