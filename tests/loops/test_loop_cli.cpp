// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen simulate on closed loops as a user runs it: the assembly report,
// a loop that cannot close and a true bifurcation, each with a clear
// one-line error that names the loop, the time and the state; the N
// four-bar through its singular positions, at the benchmark's full size.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "run_kanegen.hpp"

namespace {

kanegen_test::Result kanegen(const std::string& args) {
  static const std::filesystem::path scratch = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_CACHE, scratch, args);
}

std::string model(const std::string& name) {
  return std::string("'") + KANEGEN_SOURCE_DIR + "/models/" + name + "'";
}

int lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace

TEST_CASE("simulate reports what assembly kept", "[loops][cli]") {
  const auto r = kanegen("simulate " + model("four_bar.json") + " --t-end 0.05 --dt 0.01 -o -");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("assembly: independent coordinates crank_angle;") != std::string::npos);
  CHECK(r.out.find("E_reaction.x,E_reaction.y") != std::string::npos);
  const auto driven = kanegen("simulate " + model("slider_crank.json") + " --t-end 0.01 -o -");
  REQUIRE(driven.status == 0);
  CHECK(driven.err.find("assembly: no independent coordinate (the prescribed motion drives the mechanism)") !=
        std::string::npos);
}

TEST_CASE("a loop that cannot close is a clear error", "[loops][cli]") {
  // A coupler of 0.1 m cannot join a 0.2 m crank to a 0.5 m rocker 0.6 m away.
  const auto r = kanegen("simulate " + model("four_bar.json") + " --set b=0.1 --t-end 1 -o -");
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.out.empty());
  CHECK(lines(r.err) == lines(r.err.substr(0, r.err.find("error:"))) + 1);  // one line of error
  CHECK(r.err.find("error: assembly failed: the loops do not close") != std::string::npos);
  CHECK(r.err.find("'E.") != std::string::npos);
  CHECK(r.err.find("holding crank_angle") != std::string::npos);
  CHECK(r.err.find("q=[") != std::string::npos);
}

TEST_CASE("a true bifurcation stops the run and names the loop equation", "[loops][cli]") {
  // At rest with every link on the ground line the N four-bar may leave in
  // either branch: the cranks fall unequally and the loops cannot stay closed.
  std::string state;
  for (const char* c : {"crank0", "crank1", "crank2", "coupler1", "coupler2"})
    state += std::string(" --q0 ") + c + "_angle=0 --u0 " + c + "_angle_dot=0";
  const auto r = kanegen("simulate " + model("nfourbar2.json") + state + " --t-end 1 -o -");
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.find("error: projection onto the constraints failed: the loops cannot be kept closed") !=
        std::string::npos);
  CHECK(r.err.find("in 'L") != std::string::npos);
  CHECK(r.err.find("bifurcation") != std::string::npos);
  CHECK(r.err.find("crank0_angle=") != std::string::npos);
}

TEST_CASE("the N four-bar runs its 10 s through the singular positions", "[loops][cli]") {
  const auto r = kanegen("simulate " + model("nfourbar2.json") + " --t-end 10 --dt 1 -o -");
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(lines(r.out) == 12);  // the header and t = 0, 1, ..., 10
}

TEST_CASE("the N = 40 four-bar of the benchmark runs its 20 s on the parallelogram", "[loops][cli][slow]") {
  // 81 links, 80 loop equations that lose rank 40 at each of the cranks'
  // passes through the ground line (models/nfourbar40.json, written by
  // scripts/make_nfourbar.py).
  const auto r = kanegen("simulate " + model("nfourbar40.json") + " --t-end 20 --dt 20 -o -");
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::istringstream csv(r.out);
  std::string header, first, last;
  std::getline(csv, header);
  std::getline(csv, first);
  std::getline(csv, last);
  std::vector<double> row;
  std::istringstream fields(last);
  for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
  REQUIRE(row.size() > 41);
  CHECK(row[0] == 20.0);
  // The exact motion 53.67 theta'' = -593.505 cos(theta) (the model's
  // description), integrated independently by classical RK4 with h = 2e-5 s
  // and 1e-5 s (agreeing to 1e-10): theta(20) = -61.684499041.
  for (int crank = 1; crank <= 41; ++crank) CHECK(std::abs(row[crank] + 61.684499041) < 1e-4);
}
