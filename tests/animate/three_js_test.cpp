// SPDX-License-Identifier: GPL-2.0-or-later
// three_js_text (animate/three_js.hpp): the revision read from the one-file
// builds of npm's three (three.cjs) and Debian's libjs-three (three.min.js),
// and the refusal of a file that is not such a build.
#include "animate/three_js.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

using kanegen::animate::three_js_revision;
using kanegen::animate::three_js_text;

TEST_CASE("the revision of three.js's one-file builds", "[animate][three]") {
  CHECK(three_js_revision("const REVISION = '185';\nexports.REVISION = REVISION;") == 185);
  CHECK(three_js_revision("var t=1;REVISION=\"111\";exports.REVISION=REVISION") == 111);
  CHECK(three_js_revision("var REVISION = '111';") == 111);
  CHECK(three_js_revision("exports.REVISION = REVISION;") == -1);  // no number after it
  CHECK(three_js_revision("REVISION = '") == -1);
  CHECK(three_js_revision("") == -1);
}

namespace {

/// three_js_text with KANEGEN_THREE_JS set to a file holding text.
std::string text_of(const std::string& text) {
  // One file per process: ctest runs the test cases side by side.
  const auto path =
      std::filesystem::temp_directory_path() / ("kanegen_three_js_test." + std::to_string(getpid()) + ".js");
  std::ofstream(path, std::ios::binary) << text;
  setenv("KANEGEN_THREE_JS", path.c_str(), 1);
  try {
    std::string out = three_js_text();
    unsetenv("KANEGEN_THREE_JS");
    std::filesystem::remove(path);
    return out;
  } catch (...) {
    unsetenv("KANEGEN_THREE_JS");
    std::filesystem::remove(path);
    throw;
  }
}

}  // namespace

TEST_CASE("three_js_text takes a one-file build of r110 or later, and nothing else", "[animate][three]") {
  const std::string npm =
      "const REVISION = '185';\nexports.REVISION = REVISION;\nexports.WebGLRenderer = WebGLRenderer;";
  const std::string debian = "REVISION=\"111\";exports.WebGLRenderer=WebGLRenderer;";
  CHECK(text_of(npm) == npm);
  CHECK(text_of(debian) == debian);
  // An ES module (three.module.js, or the stub of three 0.186+), and a revision too old for the page.
  CHECK_THROWS_WITH(text_of("export * from './three.core.js'; const REVISION = '186';"),
                    Catch::Contains("is not a one-file build of three.js r110 or later"));
  CHECK_THROWS_WITH(text_of("REVISION=\"109\";exports.WebGLRenderer=WebGLRenderer;"),
                    Catch::Contains("r110 or later"));
}
