// SPDX-License-Identifier: GPL-2.0-or-later
// Where the browser viewer's three.js comes from: its CommonJS build
// (three.cjs, one file with no imports, npm's `three` pinned in
// viewer/package.json), which the page inlines, so that it opens from
// file:// with no network. kanegen ships no copy of its own: CMake finds the
// one `npm ci` put in viewer/node_modules and installs it beside kanegen.
#pragma once

#include <string>

namespace kanegen::animate {

/// The text of three.cjs, from the first of: $KANEGEN_THREE_JS (a path),
/// the installed copy (PREFIX/share/kanegen/three/three.cjs, PREFIX above
/// kanegen's bin/), the copy CMake found when it configured this build.
/// Throws std::runtime_error saying where it looked and how to get it, or
/// that the file found is not that build.
std::string three_js_text();

}  // namespace kanegen::animate
