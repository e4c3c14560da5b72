// SPDX-License-Identifier: GPL-2.0-or-later
// Scenes as VTK XML files that ParaView opens: one unstructured grid
// (.vtu, arrays inline in base64-encoded binary) per frame, and a
// collection (.pvd) that lists them with their times.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "animate/scene.hpp"

namespace kanegen::animate {

/// The .vtu text of one scene.
std::string vtu_text(const Scene& scene);

/// The .pvd text of a time series: (time, file name relative to the .pvd).
std::string pvd_text(const std::vector<std::pair<double, std::string>>& frames);

/// RFC 4648 base64 of bytes (VTK's "binary" inline format).
std::string base64(const std::vector<unsigned char>& bytes);

}  // namespace kanegen::animate
