// SPDX-License-Identifier: GPL-2.0-or-later
// simulate --energies and the work of non-conservative forces: the balance
// T + V - W_nc = (T + V)(0) on a damped, a driven and a prescribed model, and
// W_nc of a damped pendulum against the test's own quadrature of -c u^2
// over the rows.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_kanegen.hpp"

namespace fs = std::filesystem;

namespace {

using kanegen_test::Result;
using kanegen_test::slurp;

fs::path scratch() {
  static const fs::path dir = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  return dir;
}

Result kanegen(const std::string& args) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_SCRATCH_DIR "/cache", scratch(), args);
}

std::string model(const std::string& name) { return std::string(KANEGEN_MODELS_DIR) + "/" + name; }

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    REQUIRE(it != header.end());
    return static_cast<std::size_t>(it - header.begin());
  }
};

Table read_csv(const std::string& text) {
  Table t;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::istringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) t.header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream r(line);
    for (std::string cell; std::getline(r, cell, ',');) row.push_back(std::stod(cell));
    t.rows.push_back(row);
  }
  return t;
}

/// Largest |T + V - W_nc - (T + V)(0)| over the rows, and the largest T + |V|.
std::pair<double, double> balance(const Table& t) {
  const std::size_t T = t.column("kinetic_energy"), V = t.column("potential_energy"),
                    E = t.column("total_energy"), W = t.column("nonconservative_work");
  double worst = 0, scale = 0;
  for (const auto& row : t.rows) {
    worst = std::max(worst, std::abs(row[E] - row[W] - t.rows.front()[E]));
    scale = std::max(scale, row[T] + std::abs(row[V]));
  }
  return {worst, scale};
}

/// simple_pendulum.json with a viscous damper c on its hinge.
fs::path damped_pendulum(double c) {
  std::string text = slurp(model("simple_pendulum.json"));
  text.replace(text.find("\"simple_pendulum\""), 17, "\"damped_pendulum\"");
  const std::string axis = "\"axis\": [0, 1, 0],";
  text.replace(text.find(axis), axis.size(), axis + " \"damping\": " + std::to_string(c) + ",");
  const fs::path file = scratch() / "damped_pendulum.json";
  std::ofstream(file) << text;
  return file;
}

}  // namespace

TEST_CASE("a conservative model keeps three energy columns", "[energies]") {
  const Result r = kanegen("simulate " + model("simple_pendulum.json") + " --t-end 0.1 --energies --quiet");
  REQUIRE(r.status == 0);
  const Table t = read_csv(r.out);
  CHECK(t.header.back() == "total_energy");
}

TEST_CASE("damped pendulum: W_nc is the integral of -c u^2 and T + V - W_nc is constant", "[energies]") {
  const double c = 0.4;
  const Result r =
      kanegen("simulate " + damped_pendulum(c).string() + " --t-end 4 --dt 0.005 --energies --quiet");
  REQUIRE(r.status == 0);
  const Table t = read_csv(r.out);
  CHECK(t.header.back() == "nonconservative_work");
  const std::size_t u = t.column("pivot_dot"), W = t.column("nonconservative_work");
  REQUIRE(t.rows.size() == 801);
  CHECK(t.rows.front()[W] == 0.0);
  // Composite Simpson over pairs of rows of the power -c u^2 (error ~ h^4).
  double simpson = 0;
  for (std::size_t k = 2; k < t.rows.size(); k += 2) {
    const double p0 = -c * t.rows[k - 2][u] * t.rows[k - 2][u], p1 = -c * t.rows[k - 1][u] * t.rows[k - 1][u],
                 p2 = -c * t.rows[k][u] * t.rows[k][u];
    simpson += (t.rows[k][0] - t.rows[k - 2][0]) * (p0 + 4 * p1 + p2) / 6;
    CHECK(t.rows[k][W] == Approx(simpson).epsilon(1e-6).margin(1e-9));
  }
  // A good share of the energy is gone: the check above is not of a small number.
  const std::size_t E = t.column("total_energy");
  CHECK(t.rows.back()[E] - t.rows.front()[E] < -0.3);
  const auto [worst, scale] = balance(t);
  INFO("largest |T + V - W_nc - E0| = " << worst << " of T + |V| up to " << scale);
  CHECK(worst < 1e-7 * scale);
}

TEST_CASE("the --stats summary names the balance T+V-W_nc for a model with a damper", "[energies]") {
  const Result r =
      kanegen("simulate " + damped_pendulum(0.4).string() + " --t-end 1 --energies --stats --quiet");
  REQUIRE(r.status == 0);
  CHECK(r.err.find("T+V-W_nc changed by at most") != std::string::npos);
}

TEST_CASE("slider crank: the prescribed crank's drive does the work that changes T", "[energies]") {
  // Crank prescribed at 150 rad/s in a closed loop, no gravity, no damper:
  // all of d(T + V)/dt is the drive's power u_p (M udot - f - C^T lambda)_p.
  const Result r =
      kanegen("simulate " + model("slider_crank.json") + " --t-end 0.05 --dt 0.0005 --energies --quiet");
  REQUIRE(r.status == 0);
  const Table t = read_csv(r.out);
  const std::size_t W = t.column("nonconservative_work");
  double largest_work = 0;
  for (const auto& row : t.rows) largest_work = std::max(largest_work, std::abs(row[W]));
  const auto [worst, scale] = balance(t);
  INFO("largest |W_nc| " << largest_work << ", largest |T + V - W_nc - E0| " << worst << " of " << scale);
  CHECK(largest_work > 0.1 * scale);
  CHECK(worst < 1e-6 * scale);
}

TEST_CASE("Andrews' squeezer: the motor torque and the spring balance T + V - W_nc", "[energies]") {
  const Result r =
      kanegen("simulate " + model("andrews_squeezer.json") + " --t-end 0.003 --dt 0.0001 --energies --quiet");
  REQUIRE(r.status == 0);
  const Table t = read_csv(r.out);
  const std::size_t W = t.column("nonconservative_work");
  const auto [worst, scale] = balance(t);
  INFO("W_nc(end) " << t.rows.back()[W] << ", largest |T + V - W_nc - E0| " << worst << " of " << scale);
  // In 3 ms the motor's work is a small part of the spring's energy, but far above the balance's error.
  CHECK(std::abs(t.rows.back()[W]) > 1e-3 * scale);
  CHECK(worst < 1e-6 * std::abs(t.rows.back()[W]));
}

TEST_CASE("spin-up beam: prescribed hub, structural damping, elastic tree", "[energies]") {
  const Result r =
      kanegen("simulate " + model("spin_up_beam_linear.json") + " --t-end 0.5 --dt 0.01 --energies --quiet");
  REQUIRE(r.status == 0);
  const Table t = read_csv(r.out);
  const std::size_t W = t.column("nonconservative_work");
  const auto [worst, scale] = balance(t);
  INFO("W_nc(end) " << t.rows.back()[W] << ", largest |T + V - W_nc - E0| " << worst << " of " << scale);
  CHECK(std::abs(t.rows.back()[W]) > 0.1 * scale);
  CHECK(worst < 1e-6 * scale);
}

TEST_CASE("implicit methods: W_nc by the trapezoid rule over the rows", "[energies]") {
  const Result r = kanegen("simulate " + damped_pendulum(0.4).string() +
                           " --t-end 2 --dt 0.001 --integrator implicit --energies --quiet");
  REQUIRE(r.status == 0);
  const Table t = read_csv(r.out);
  const auto [worst, scale] = balance(t);
  INFO("largest |T + V - W_nc - E0| = " << worst << " of " << scale);
  CHECK(worst < 1e-5 * scale);
}

// Every integrator with --energies on a model with a damper: the work column
// is carried in the state (explicit methods) or summed over the rows
// (implicit ones); radau and bdf once wrote it one element past their
// nq + nu buffers, which only a sanitized run (.ci/run part 2) reports.
TEST_CASE("every integrator keeps T + V - W_nc with a damper", "[energies]") {
  const std::string damped = damped_pendulum(0.4).string();
  const struct {
    const char* integrator;
    double balance;  // bound on |T + V - W_nc - E0| / (T + |V|), 5-10 times what each method gave
  } runs[] = {       // measured: 1.2e-13, 8.9e-10, 2.0e-8, 2.0e-8, 1.3e-7, 1.5e-7
              {"rk4", 1e-12},  {"dopri5", 1e-8}, {"implicit", 1e-7},
              {"radau", 1e-7}, {"bdf", 1e-6},    {"genalpha", 1e-6}};
  for (const auto& run : runs) {
    DYNAMIC_SECTION(run.integrator) {
      const Result r = kanegen("simulate " + damped + " --t-end 2 --dt 0.001 --integrator " + run.integrator +
                               " --energies --quiet");
      INFO(r.err);
      REQUIRE(r.status == 0);
      const Table t = read_csv(r.out);
      REQUIRE(t.rows.size() == 2001);
      const std::size_t W = t.column("nonconservative_work");
      const auto [worst, scale] = balance(t);
      INFO("W_nc(end) " << t.rows.back()[W] << ", largest |T + V - W_nc - E0| " << worst << " of " << scale);
      CHECK(t.rows.back()[W] < -0.05 * scale);  // the damper took a good share of the energy (0.06)
      CHECK(worst < run.balance * scale);
    }
  }
}
