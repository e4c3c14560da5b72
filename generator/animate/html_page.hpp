// SPDX-License-Identifier: GPL-2.0-or-later
// The one self-contained HTML file of `kanegen animate --format html`: the
// viewer's page (templates/viewer.html.in, compiled into kanegen) with
// three.js and the run's data put into it.
#pragma once

#include <string>

namespace kanegen::animate {

/// The page with three.js's CommonJS build (three_js_text) in an IIFE that
/// sets window.THREE, and the JSON of viewer_json. Throws std::runtime_error
/// if either text could end its <script> element early.
std::string viewer_page(const std::string& three_js, const std::string& data_json);

}  // namespace kanegen::animate
