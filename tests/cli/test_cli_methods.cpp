// SPDX-License-Identifier: GPL-2.0-or-later
// Every row of the runtime's registry of integrators (methods.hpp) through
// kanegen, on a shipped model: its name is accepted, the Jacobian kernels are
// generated exactly when the row says it needs them (else the implicit ones
// fail), and --stats names the method that ran. A new method is run here
// without a line of its own. Part of test_cli.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "../support/run_kanegen.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen_test {

// The registry's names as the unknown-integrator message lists them: a new
// method changes the message, not the tests.
std::string known_integrators() {
  std::string known;
  for (const std::string& name : kanegen::runtime::method_names())
    known += (known.empty() ? "" : ", ") + name;
  return known;
}

}  // namespace kanegen_test

namespace {

kanegen_test::Result simulate(const std::string& args) {
  // Its own scratch directory: test_cli.cpp's is wiped when first used.
  static const std::filesystem::path scratch = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR "/methods");
  return kanegen_test::run_kanegen(KANEGEN_EXE, KANEGEN_SCRATCH_DIR "/cache", scratch, "simulate " + args);
}

}  // namespace

TEST_CASE("simulate runs every registered integrator on a shipped model", "[cli]") {
  const std::string pendulum = std::string(KANEGEN_MODELS_DIR) + "/double_pendulum.json";
  for (const kanegen::runtime::MethodSpec& m : kanegen::runtime::kMethods) {
    INFO(m.name);
    const kanegen_test::Result r = simulate(pendulum + " --t-end 0.1 --stats --quiet --integrator " + m.name);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 12);  // the header and t = 0, 0.01, ..., 0.1
    const std::string ran = kanegen::runtime::resolved_spec(m.method).name;
    CHECK(r.err.find("stats: integrator=" + ran + " ") != std::string::npos);
  }
}
