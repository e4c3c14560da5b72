// SPDX-License-Identifier: GPL-2.0-or-later
// Inputs the fuzzers found (tests/data/fuzz_regressions/{json,urdf,expression}),
// replayed through the fuzz targets' own checks: each loads or ends in one
// ModelError, never a crash, another exception or a broken invariant.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/harness.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> inputs(const std::string& kind) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(KANEGEN_FUZZ_REGRESSIONS) / kind))
    if (entry.is_regular_file() && entry.path().filename().string()[0] != '.') files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

void replay(const std::string& kind, void (*check)(const std::uint8_t*, std::size_t)) {
  const std::vector<fs::path> files = inputs(kind);
  REQUIRE(!files.empty());  // an emptied directory would make this test vacuous
  for (const fs::path& file : files) {
    INFO(file.string());
    std::ifstream in(file, std::ios::binary);
    REQUIRE(in);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    try {
      check(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const kanegen::fuzz::HarnessFailure& e) {
      FAIL(e.what());
    }
  }
}

}  // namespace

TEST_CASE("fuzz regressions: JSON models load or fail with a ModelError", "[fuzz]") {
  replay("json", kanegen::fuzz::json_model);
}

TEST_CASE("fuzz regressions: URDF files load or fail with a ModelError", "[fuzz]") {
  replay("urdf", kanegen::fuzz::urdf_model);
}

TEST_CASE("fuzz regressions: expressions are refused with a caret or read by GiNaC", "[fuzz]") {
  replay("expression", kanegen::fuzz::expression);
}
