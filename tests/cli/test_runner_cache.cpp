// SPDX-License-Identifier: GPL-2.0-or-later
// The runner cache as users meet it: several kanegen processes building one
// new model at once, an entry changed after it was built (an edited source, a
// replaced runner), and a cache directory others may write to
// (generator/runner/runner_cache.hpp, docs/errors.md#security).
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
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

const std::string kModel = std::string(KANEGEN_MODELS_DIR) + "/double_pendulum.json";

/// A new, empty cache directory for one test.
fs::path fresh_cache(const std::string& name) {
  const fs::path cache = scratch() / name;
  fs::remove_all(cache);
  return cache;
}

Result simulate(const fs::path& cache, const fs::path& csv) {
  return kanegen_test::run_kanegen(KANEGEN_EXE, cache.string(), scratch(),
                                   "simulate '" + kModel + "' --t-end 1 -o '" + csv.string() + "'");
}

/// The one entry of a cache that has built one model.
fs::path entry_of(const fs::path& cache) {
  for (const auto& entry : fs::directory_iterator(cache))
    if (entry.is_directory()) return entry.path();
  FAIL("no entry in " << cache);
  return {};
}

bool compiled(const Result& r) { return r.err.find("kanegen: compiling") != std::string::npos; }

}  // namespace

TEST_CASE("four simulate processes of a new model at once build it once and write identical CSVs",
          "[cache]") {
  const fs::path cache = fresh_cache("concurrent");
  const fs::path dir = scratch() / "concurrent_runs";
  fs::create_directories(dir);
  std::string script;
  for (int i = 0; i < 4; ++i) {
    const std::string k = std::to_string(i);
    script += "(KANEGEN_CACHE_DIR='" + cache.string() + "' '" KANEGEN_EXE "' simulate '" + kModel +
              "' --t-end 1 -o '" + (dir / ("out" + k + ".csv")).string() + "' 2>'" +
              (dir / ("err" + k + ".txt")).string() + "'; echo $? >'" +
              (dir / ("status" + k + ".txt")).string() + "') &\n";
  }
  script += "wait\n";
  REQUIRE(std::system(script.c_str()) == 0);
  const std::string first = slurp(dir / "out0.csv");
  REQUIRE(first.size() > 1000);
  int compiles = 0;
  for (int i = 0; i < 4; ++i) {
    const std::string k = std::to_string(i);
    const std::string err = slurp(dir / ("err" + k + ".txt"));
    INFO("process " << k << ": " << err);
    CHECK(slurp(dir / ("status" + k + ".txt")) == "0\n");
    CHECK(slurp(dir / ("out" + k + ".csv")) == first);
    if (err.find("kanegen: compiling") != std::string::npos) ++compiles;
  }
  // The entry's lock: one process builds, the others wait for its runner.
  CHECK(compiles == 1);
}

TEST_CASE("a cached source changed after the build is detected and the runner rebuilt", "[cache]") {
  const fs::path cache = fresh_cache("edited_source");
  const Result built = simulate(cache, scratch() / "edited_a.csv");
  REQUIRE(built.status == 0);
  const fs::path entry = entry_of(cache);
  std::ofstream(entry / "double_pendulum.cpp", std::ios::app) << "// edited\n";
  const Result again = simulate(cache, scratch() / "edited_b.csv");
  INFO(again.err);
  REQUIRE(again.status == 0);
  CHECK(
      again.err.find("is not as it was built (double_pendulum.cpp changed after it was built); rebuilding") !=
      std::string::npos);
  CHECK(compiled(again));
  CHECK(slurp(scratch() / "edited_b.csv") == slurp(scratch() / "edited_a.csv"));
  CHECK(slurp(entry / "double_pendulum.cpp").find("// edited") == std::string::npos);
  // Rebuilt and sealed again: the next run uses it as it is.
  const Result third = simulate(cache, scratch() / "edited_c.csv");
  REQUIRE(third.status == 0);
  CHECK(!compiled(third));
  CHECK(third.err.find("not as it was built") == std::string::npos);
}

TEST_CASE("a replaced runner in the cache is never run", "[cache]") {
  const fs::path cache = fresh_cache("replaced_runner");
  REQUIRE(simulate(cache, scratch() / "replaced_a.csv").status == 0);
  const fs::path entry = entry_of(cache), marker = scratch() / "replaced_runner_ran";
  fs::remove(marker);
  std::ofstream(entry / "runner", std::ios::trunc) << "#!/bin/sh\ntouch '" << marker.string() << "'\n";
  const Result again = simulate(cache, scratch() / "replaced_b.csv");
  INFO(again.err);
  REQUIRE(again.status == 0);
  CHECK(!fs::exists(marker));
  CHECK(again.err.find("(runner changed after it was built); rebuilding") != std::string::npos);
  CHECK(slurp(scratch() / "replaced_b.csv") == slurp(scratch() / "replaced_a.csv"));
  // A deleted manifest counts as a change too.
  fs::remove(entry / "manifest");
  const Result third = simulate(cache, scratch() / "replaced_c.csv");
  REQUIRE(third.status == 0);
  CHECK(third.err.find("it has no manifest") != std::string::npos);
  CHECK(compiled(third));
}

TEST_CASE("a runner cache that other users may write to is refused", "[cache]") {
  const fs::path cache = fresh_cache("shared");
  fs::create_directories(cache);
  REQUIRE(::chmod(cache.c_str(), 0777) == 0);
  const Result r = simulate(cache, scratch() / "shared.csv");
  INFO(r.err);
  CHECK(r.status != 0);
  CHECK(r.err.find(cache.string() +
                   ": the runner cache is writable by other users (mode 0777); run chmod go-w") !=
        std::string::npos);
  CHECK(fs::is_empty(cache));  // nothing built, nothing run
  // A new cache directory is made private.
  const fs::path made = fresh_cache("made");
  REQUIRE(simulate(made, scratch() / "made.csv").status == 0);
  CHECK((fs::status(made).permissions() & fs::perms::all) == fs::perms::owner_all);
}
