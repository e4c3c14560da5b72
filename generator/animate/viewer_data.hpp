// SPDX-License-Identifier: GPL-2.0-or-later
// What the browser viewer of `kanegen animate --format html` draws, as the
// JSON document its page reads (templates/viewer.html.in): the bodies (name,
// joint and its axis, the shapes of a rigid part (animate/shapes.hpp), a beam's or mesh's
// undeformed nodes and a mesh's surface, all in body frames), then per frame
// each body's world pose and each elastic node's displacement (body frame,
// unscaled: the page magnifies it), and the result's columns for the plots.
// Poses and displacements are little-endian float32 arrays in base64, which
// is what the page's WebGL draws with anyway.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "animate/result_table.hpp"
#include "animate/shapes.hpp"
#include "numeric/instance.hpp"

namespace kanegen::animate {

struct ViewerRun {
  std::string model_name;
  const numeric::Instance* instance = nullptr;
  const ResultTable* table = nullptr;
  std::vector<std::size_t> rows;           ///< the table's rows drawn, in order
  std::vector<int> coordinate_columns;     ///< per coordinate of the instance, its column in the table
  double scale = 1;                        ///< the magnification the page starts with
  std::vector<std::vector<Shape>> shapes;  ///< per body, its rigid part's (body_shapes)
};

/// The JSON document; every name in it goes through script_json_string, so
/// it may stand in an HTML <script> element as it is.
std::string viewer_json(const ViewerRun& run);

/// Little-endian float32 values in base64 (the page reads them with a DataView).
std::string float32_base64(const std::vector<float>& values);

}  // namespace kanegen::animate
