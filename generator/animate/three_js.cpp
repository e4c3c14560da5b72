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

int three_js_revision(const std::string& text) {
  for (std::size_t at = text.find("REVISION"); at != std::string::npos; at = text.find("REVISION", at + 1)) {
    std::size_t k = at + 8;
    while (k < text.size() && text[k] == ' ') ++k;
    if (k >= text.size() || text[k] != '=') continue;
    ++k;
    while (k < text.size() && text[k] == ' ') ++k;
    if (k >= text.size() || (text[k] != '\'' && text[k] != '"')) continue;
    int revision = 0, digits = 0;
    for (++k; k < text.size() && digits < 6 && text[k] >= '0' && text[k] <= '9'; ++k, ++digits)
      revision = 10 * revision + (text[k] - '0');
    if (digits > 0 && k < text.size() && (text[k] == '\'' || text[k] == '"')) return revision;
  }
  return -1;
}

namespace {

/// The text, if it is a one-file CommonJS (npm's three.cjs) or UMD (Debian's three.min.js) build
/// of a revision the page works with; a later npm three ships a stub in place of three.cjs that
/// only re-exports the ES module, which a page cannot use.
std::string checked(std::string text, const std::string& path) {
  const bool one_file = text.find("exports.WebGLRenderer = WebGLRenderer") != std::string::npos ||
                        text.find("exports.WebGLRenderer=WebGLRenderer") != std::string::npos;
  if (!one_file || three_js_revision(text) < oldest_three_revision)
    throw std::runtime_error(
        "--format html: " + path + " is not a one-file build of three.js r" +
        std::to_string(oldest_three_revision) +
        " or later (npm's three 0.186 and later ship a stub in place of build/three.cjs); install the "
        "version viewer/package.json pins with `npm ci` in viewer/, or Debian's libjs-three, or set "
        "KANEGEN_THREE_JS to build/three.cjs of three 0.185");
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
  if (read(debian_three_js, &text)) return checked(text, tried.back());
  std::string where;
  for (const std::string& path : tried) where += (where.empty() ? "" : ", ") + path;
  throw std::runtime_error(
      "--format html: three.js is not found (looked for " + where +
      "); install Debian's libjs-three (apt-get install libjs-three), or npm's with `npm ci` in viewer/ "
      "of kanegen's source and configure and build again (scripts/install-deps.sh does both), or set "
      "KANEGEN_THREE_JS to its build/three.cjs; --format vtk needs none");
}

}  // namespace kanegen::animate
