// SPDX-License-Identifier: GPL-2.0-or-later
// The command line on everything that can go wrong, as a user sees it: every
// bad model in tests/data/bad_models ends in one "error: FILE: PLACE: ...; fix"
// and no output; run-time failures of `kanegen simulate` (a singular mass
// matrix, a NaN, a motion that overflows, a tolerance that cannot be met, too
// many steps, a signal) end in one line naming the time and the state, and
// keep the rows computed before; bad values on the command line are refused.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
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

/// Runs kanegen (arguments in shell syntax) with a private runner cache.
Result kanegen(const std::string& args) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_SCRATCH_DIR "/cache", scratch(), args);
}

std::string source(const std::string& relative) { return std::string(KANEGEN_SOURCE_DIR) + "/" + relative; }
const std::string kModel = source("tests/data/models/runtime_failures.json");

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The run failed (exit 1) with exactly one line on stderr, "error: ...
/// at t=T, state [slide=X, slide_dot=V]"; returns T.
double failed_at(const Result& r, const std::string& problem) {
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(lines(r.err).size() == 1);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK_THAT(r.err, Catch::Contains(problem));
  std::smatch m;
  const std::regex where(" at t=([-+0-9.e]+), state \\[slide=[^,\\]]+, slide_dot=[^,\\]]+\\]");
  REQUIRE(std::regex_search(r.err, m, where));
  return std::stod(m[1]);
}

/// The CSV rows written before the failure: the header and then rows with t < t_fail.
void rows_kept(const fs::path& csv, double t_fail, std::size_t at_least) {
  const std::vector<std::string> rows = lines(slurp(csv));
  REQUIRE(rows.size() >= at_least + 1);
  CHECK(rows.front() == "t,slide,slide_dot");
  for (std::size_t i = 1; i < rows.size(); ++i)
    CHECK(std::stod(rows[i].substr(0, rows[i].find(','))) <= t_fail);
}

}  // namespace

TEST_CASE("every bad model ends in one clear error and writes nothing", "[reliability][cli]") {
  std::vector<fs::path> models;
  for (const auto& entry : fs::directory_iterator(source("tests/data/bad_models")))
    models.push_back(entry.path());
  std::sort(models.begin(), models.end());
  REQUIRE(models.size() >= 50);
  const fs::path dir = scratch() / "bad_out";
  for (const fs::path& model : models) {
    INFO(model.string());
    const Result r = kanegen("generate '" + model.string() + "' -o '" + dir.string() + "'");
    INFO(r.err);
    CHECK(r.status == 2);  // a bad model, not a crash (which would be 128 + signal or -1)
    CHECK(r.err.rfind("error: " + model.string() + ": ", 0) == 0);
    // "FILE: PLACE: problem; fix": a place, and a fix after the last "; ".
    const std::string message = r.err.substr(7 + model.string().size() + 2);
    CHECK(message.find(": ") != std::string::npos);
    CHECK(message.find("; ") != std::string::npos);
    // One line, except that an expression is shown with a caret under the culprit.
    const auto n = lines(r.err).size();
    CHECK((n == 1 || (n == 3 && r.err.find("expression\n") != std::string::npos)));
    CHECK(r.out.empty());
    CHECK(!fs::exists(dir));
  }
}

TEST_CASE("an expression naming a parameter that is never defined is shown with a caret",
          "[reliability][cli]") {
  const std::string model = source("tests/data/bad_models/undefined_parameter.json");
  const Result r = kanegen("generate " + model + " -o " + (scratch() / "undefined").string());
  CHECK(r.status == 2);
  CHECK(r.err == "error: " + model +
                     ": /bodies/0/com/2: unknown name 'length' in expression\n"
                     "  -length/2\n"
                     "   ^; define it under /parameters or fix the spelling\n");
  const std::string null_value = source("tests/data/bad_models/parameter_without_value.json");
  const Result n = kanegen("generate " + null_value + " -o " + (scratch() / "undefined").string());
  CHECK(n.status == 2);
  CHECK(n.err == "error: " + null_value +
                     ": /parameters/l: wrong type: expected a number, found null; write a number\n");
}

TEST_CASE("the test model simulates with its defaults", "[reliability][cli]") {
  // So that each failure below comes from the one change it makes.
  const fs::path csv = scratch() / "ok.csv";
  const Result r = kanegen("simulate " + kModel + " --t-end 1 --dt 0.1 --quiet -o " + csv.string());
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  CHECK(lines(slurp(csv)).size() == 12);
}

TEST_CASE("a mass matrix singular at run time names the time and the state", "[reliability][cli]") {
  const Result r = kanegen("simulate " + kModel + " --t-end 1 --quiet --set m=0");
  CHECK(failed_at(r,
                  "mass matrix is not positive definite at coordinate 'slide' (pivot 1 of its LDL^T "
                  "factorisation is not positive): joint 'slide' moves body 'block', which has a zero") ==
        0.0);
}

TEST_CASE("a NaN from a parameter value names the derivative, the time and the state", "[reliability][cli]") {
  // sqrt(f) with f = -1.
  const Result r = kanegen("simulate " + kModel + " --t-end 1 --quiet --set f=-1");
  CHECK(failed_at(r, "d(slide_dot)/dt = -nan") == 0.0);
}

namespace {

/// The runner kanegen built for kModel (by an earlier call), run directly:
/// for values kanegen itself refuses before running (a negative stiffness).
Result runner(const std::string& args) {
  REQUIRE(kanegen("eval " + kModel + " --quiet").status == 0);
  for (const auto& entry : fs::recursive_directory_iterator(KANEGEN_SCRATCH_DIR "/cache"))
    if (entry.path().filename() == "runner" && fs::exists(entry.path().parent_path() / "runtime_failures.hpp"))
      return kanegen_test::run_kanegen(entry.path().string(), KANEGEN_SCRATCH_DIR "/cache", scratch(), args);
  FAIL("no runner for " << kModel);
  return {};
}

}  // namespace

TEST_CASE("a motion that overflows mid-run stops there and keeps the rows before", "[reliability][cli]") {
  // Negative stiffness: x grows like exp(1000 t) and overflows near t = 0.7.
  // kanegen refuses it at once (tested in tests/cli); the runner must still
  // stop cleanly on such a motion.
  CHECK(kanegen("simulate " + kModel + " --t-end 2 --quiet --set k=-1e6").status == 2);
  for (const char* integrator : {"dopri5", "rk4"}) {
    INFO(integrator);
    const fs::path csv = scratch() / (std::string("overflow_") + integrator + ".csv");
    const Result r =
        runner("simulate --t-end 2 --set k=-1e6 --integrator " + std::string(integrator) + " -o " + csv.string());
    const double t = failed_at(r, "right-hand side returned d(slide");
    CHECK(t > 0.5);
    CHECK(t < 1.5);
    CHECK_THAT(r.err, Catch::Contains("inf"));
    rows_kept(csv, t, 50);
  }
}

TEST_CASE("a tolerance that cannot be met stops with the time and the state", "[reliability][cli]") {
  const fs::path csv = scratch() / "tolerance.csv";
  const Result r =
      kanegen("simulate " + kModel + " --t-end 1 --quiet --rtol 1e-300 --atol 1e-300 -o " + csv.string());
  const double t = failed_at(r, "too tight a tolerance");
  CHECK(t < 1.0);
  rows_kept(csv, t, 1);  // the initial state
}

TEST_CASE("running out of steps says so, with the time and the state", "[reliability][cli]") {
  // rk4 with dt 0.01 needs 200000 steps; the limit given is 100000.
  const fs::path csv = scratch() / "steps.csv";
  const Result r =
      kanegen("simulate " + kModel + " --t-end 2000 --integrator rk4 --max-steps 100000 --quiet -o " + csv.string());
  CHECK(failed_at(r, "reached max_steps = 100000 before t_end = 2000") == Approx(1000.0));
  rows_kept(csv, 1000.0, 100001);
}

TEST_CASE("a simulation stopped by a signal keeps its rows and says where it stopped", "[reliability][cli]") {
  // Compile the runner first, so that the signal reaches a running simulation.
  REQUIRE(kanegen("simulate " + kModel + " --t-end 0.1 --quiet").status == 0);
  for (const char* signal : {"INT", "TERM"}) {
    INFO(signal);
    const fs::path csv = scratch() / (std::string("signal_") + signal + ".csv");
    const fs::path err = scratch() / "signal_stderr.txt", status = scratch() / "signal_status.txt";
    fs::remove(csv);
    // A run of 1e8 steps, signalled once it has written 1000 rows.
    const fs::path script = scratch() / "signal.sh";
    std::ofstream(script) << "KANEGEN_CACHE_DIR='" KANEGEN_SCRATCH_DIR "/cache' '" KANEGEN_EXE "' simulate '" << kModel
                          << "' --t-end 1e5 --dt 1e-3 --integrator rk4 --max-steps 1000000000 --quiet -o '"
                          << csv.string() << "' 2>'" << err.string() << "' &\n"
                          << "pid=$!; i=0\n"
                          << "while [ \"$(cat '" << csv.string() << "' 2>/dev/null | wc -l)\" -lt 1000 ] && "
                          << "[ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done\n"
                          << "kill -" << signal << " $pid; wait $pid; echo $? >'" << status.string() << "'\n";
    REQUIRE(std::system(("sh '" + script.string() + "'").c_str()) == 0);
    const std::string message = slurp(err);
    INFO(message);
    CHECK(std::stoi(slurp(status)) == 128 + (std::string(signal) == "INT" ? 2 : 15));
    CHECK(lines(message).size() == 1);
    CHECK_THAT(message, Catch::StartsWith(std::string("error: interrupted by SIG") + signal + "; "));
    std::smatch m;
    REQUIRE(std::regex_search(message, m, std::regex("; ([0-9]+) rows written to .*, up to t=([-+0-9.e]+) of t_end=1")));
    // Every row the message counts is in the file, complete, and the last is at the time it names.
    const std::vector<std::string> rows = lines(slurp(csv));
    REQUIRE(rows.size() == std::stoul(m[1]) + 1);
    CHECK(rows.size() > 1000);
    for (std::size_t i = 1; i < rows.size(); ++i) CHECK(std::count(rows[i].begin(), rows[i].end(), ',') == 2);
    CHECK(std::stod(rows.back().substr(0, rows.back().find(','))) == Approx(std::stod(m[2])));
  }
}

TEST_CASE("bad values on the command line are refused with the known names", "[reliability][cli]") {
  struct Case {
    const char* args;
    const char* message;
  };
  for (const Case& c : {Case{"--set nope=1", "unknown parameter 'nope' in --set; known parameters: m, k, f"},
                        Case{"--set m=abc", "invalid number 'abc' for --set"},
                        Case{"--set m=nan", "invalid number 'nan' for --set"},
                        Case{"--q0 nope=1", "unknown name 'nope' in --q0; known coordinates: slide"}}) {
    INFO(c.args);
    const Result r = kanegen("simulate " + kModel + " --t-end 1 --quiet " + c.args);
    CHECK(r.status == 2);
    CHECK(r.err == std::string("error: ") + c.message + "\n");
    CHECK(r.out.empty());
  }
  for (const char* args : {"--t-end -1", "--t-end 1 --dt 0", "--t-end 1 --rtol -1", "--t-end x"}) {
    INFO(args);
    const Result r = kanegen("simulate " + kModel + " --quiet " + args);
    CHECK(r.status != 0);
    CHECK(r.status < 128);
    CHECK(!r.err.empty());
    CHECK(r.out.empty());
  }
}
