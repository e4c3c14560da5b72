// SPDX-License-Identifier: GPL-2.0-or-later
// Licensing, as docs/licensing.md states it: the SPDX line of every source
// file of the repository (by its place: MIT under runtime/, templates/,
// cmake/ and examples/, GPL-2.0-or-later elsewhere), the header of freshly
// generated code (MIT and the output line), the license files, and
// THIRD_PARTY.md naming every dependency.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "run_kanegen.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = KANEGEN_SOURCE_DIR;
const std::string kOutputLine =
    "This file is kanegen's output: you may use, copy, modify and distribute it under any terms you choose";

/// The first `count` lines of a file.
std::vector<std::string> head(const fs::path& file, int count) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; lines.size() < static_cast<std::size_t>(count) && std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

/// The SPDX identifier in the first three lines (after a shebang), or "".
std::string spdx(const fs::path& file) {
  static const std::regex line("^(//|#) SPDX-License-Identifier: ([A-Za-z0-9.+-]+)$");
  for (const std::string& l : head(file, 3)) {
    std::smatch m;
    if (std::regex_match(l, m, line)) return m[2];
  }
  return "";
}

/// Source files: C++, templates and CMake inputs, CMake files, shell and
/// Python scripts, and CI's script; not data (models, meshes, references,
/// dictionaries) nor documentation nor generated/ (checked as output below).
bool is_source(const fs::path& relative) {
  const std::string name = relative.filename().string(), ext = relative.extension().string();
  if (name == "CMakeLists.txt" || relative == fs::path(".ci/run")) return true;
  return ext == ".cpp" || ext == ".hpp" || ext == ".h" || ext == ".in" || ext == ".cmake" || ext == ".sh" ||
         ext == ".py";
}

std::string expected_license(const fs::path& relative) {
  const std::string top = relative.begin()->string();
  return top == "runtime" || top == "templates" || top == "cmake" || top == "examples" ? "MIT"
                                                                                       : "GPL-2.0-or-later";
}

}  // namespace

TEST_CASE("every source file names its license in an SPDX line", "[licensing]") {
  const std::vector<std::string> trees = {"generator", "runtime", "templates", "cmake", "examples", "tests",
                                          "bench",     "fuzz",    "scripts",   ".ci",   "python"};
  std::vector<fs::path> files = {kRoot / "CMakeLists.txt"};
  for (const std::string& tree : trees)
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / tree)) {
      if (!entry.is_regular_file()) continue;
      const fs::path relative = fs::relative(entry.path(), kRoot);
      const std::string text = relative.string();
      // Data under tests: models, meshes, fuzz inputs, reference results.
      if (text.rfind("tests/data/", 0) == 0 || text.find("/data/") != std::string::npos) continue;
      if (is_source(relative)) files.push_back(entry.path());
    }
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() > 200);
  int mit = 0;
  for (const fs::path& file : files) {
    const fs::path relative = fs::relative(file, kRoot);
    INFO(relative.string());
    const std::string expected = expected_license(relative);
    CHECK(spdx(file) == expected);
    mit += expected == "MIT";
  }
  CHECK(mit > 20);  // runtime, templates, cmake and examples were found
}

TEST_CASE("generated code carries the MIT identifier and says it is kanegen's output", "[licensing]") {
  const fs::path scratch = kanegen_test::process_scratch(KANEGEN_SCRATCH_DIR);
  const fs::path out = scratch / "generated";
  const kanegen_test::Result r = kanegen_test::run_kanegen(
      KANEGEN_EXE, KANEGEN_CACHE, scratch,
      "generate '" + (kRoot / "models/four_bar.json").string() + "' -o '" + out.string() + "' --quiet");
  INFO(r.err);
  REQUIRE(r.status == 0);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    INFO(entry.path().string());
    const std::vector<std::string> lines = head(entry.path(), 2);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0] == "// SPDX-License-Identifier: MIT");
    CHECK(lines[1].rfind("// " + kOutputLine, 0) == 0);
    ++files;
  }
  CHECK(files == 3);  // the header, the kernels and the runner
}

TEST_CASE("the license files exist and THIRD_PARTY.md names every dependency", "[licensing]") {
  for (const char* file : {"LICENSE", "LICENSES/MIT.txt", "LICENSES/GPL-2.0-or-later.txt",
                           "LICENSES/MIT-three.js.txt", "THIRD_PARTY.md", "docs/licensing.md"}) {
    INFO(file);
    CHECK(fs::file_size(kRoot / file) > 500);
  }
  const std::string license = kanegen_test::slurp(kRoot / "LICENSE");
  CHECK(license.find("Output exception") != std::string::npos);
  CHECK(kanegen_test::slurp(kRoot / "LICENSES/GPL-2.0-or-later.txt").find("GNU GENERAL PUBLIC LICENSE") !=
        std::string::npos);
  const std::string third = kanegen_test::slurp(kRoot / "THIRD_PARTY.md");
  for (const char* dependency : {"GiNaC", "CLN", "Eigen", "Spectra", "nlohmann-json", "Catch2", "urdfdom",
                                 "TinyXML-2", "CLI11", "valijson", "MuJoCo", "Google Benchmark",
                                 "SUNDIALS (CVODE)", "three.js", "Selenium", "pybind11", "NumPy"}) {
    INFO(dependency);
    CHECK(third.find(std::string("| ") + dependency + " |") != std::string::npos);
  }
}
