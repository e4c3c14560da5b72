// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/three_js.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#ifndef KANEGEN_THREE_JS_BUILD
#define KANEGEN_THREE_JS_BUILD ""
#endif

namespace kanegen::animate {
namespace fs = std::filesystem;

namespace {

/// The text, if it is three's one-file CommonJS build; a later three ships a
/// stub in its place that only re-exports the ES module, which a page cannot use.
std::string checked(std::string text, const std::string& path) {
  if (text.find("exports.WebGLRenderer = WebGLRenderer") == std::string::npos)
    throw std::runtime_error(
        "--format html: " + path +
        " is not three.js's one-file CommonJS build (three 0.186 and later ship a stub in "
        "its place); install the version viewer/package.json pins with `npm ci` in viewer/, "
        "or set KANEGEN_THREE_JS to build/three.cjs of three 0.185");
  return text;
}

}  // namespace

std::string three_js_text() {
  std::vector<std::string> tried;
  const auto read = [&](const fs::path& path, std::string* text) {
    tried.push_back(path.string());
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return false;
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    *text = out.str();
    return static_cast<bool>(in) && !text->empty();
  };
  std::string text;
  if (const char* given = std::getenv("KANEGEN_THREE_JS"); given && *given) {
    if (read(given, &text)) return checked(text, given);
    throw std::runtime_error(
        std::string("KANEGEN_THREE_JS=") + given +
        ": not a readable file; give the path of three.js's build/three.cjs, or unset it");
  }
  std::error_code error;
  const fs::path exe = fs::canonical("/proc/self/exe", error);
  if (!error && read(exe.parent_path().parent_path() / "share/kanegen/three/three.cjs", &text))
    return checked(text, tried.back());
  if (*KANEGEN_THREE_JS_BUILD && read(KANEGEN_THREE_JS_BUILD, &text)) return checked(text, tried.back());
  std::string where;
  for (const std::string& path : tried) where += (where.empty() ? "" : ", ") + path;
  throw std::runtime_error(
      "--format html: three.js is not found (looked for " + where +
      "); install it with `npm ci` in viewer/ of kanegen's source (scripts/install-deps.sh does) and "
      "configure and build again, or set KANEGEN_THREE_JS to its build/three.cjs; --format vtk needs none");
}

}  // namespace kanegen::animate
