// SPDX-License-Identifier: GPL-2.0-or-later
// Where the browser viewer's three.js comes from: a one-file build with no
// imports that the page inlines, so that it opens from file:// with no
// network. Either npm's `three` pinned in viewer/package.json (its CommonJS
// build, three.cjs: CMake finds the one `npm ci` put in viewer/node_modules
// and installs it beside kanegen), or Debian's libjs-three (r111, a UMD
// build, which the same CommonJS wrapper in the page loads), for a machine
// that reaches Debian's archive but not the npm registry. kanegen ships no
// copy of its own.
#pragma once

#include <string>

namespace kanegen::animate {

/// Debian's libjs-three, the last place three_js_text looks.
inline constexpr const char* debian_three_js = "/usr/share/javascript/three/build/three.min.js";

/// The oldest three.js revision the page works with (BufferGeometry.setAttribute and
/// BufferAttribute.setUsage came in r110; r111 is Debian 12's).
inline constexpr int oldest_three_revision = 110;

/// The text of three.js, from the first of: $KANEGEN_THREE_JS (a path),
/// the installed copy (PREFIX/share/kanegen/three/three.cjs, PREFIX above
/// kanegen's bin/), the copy CMake found when it configured this build
/// (npm's), Debian's libjs-three. Throws std::runtime_error saying where it
/// looked and how to get it, or that the file found is not such a build.
std::string three_js_text();

/// The revision a three.js text declares (`REVISION = '111'`), or -1.
int three_js_revision(const std::string& text);

}  // namespace kanegen::animate
