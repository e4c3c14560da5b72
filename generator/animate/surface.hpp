// SPDX-License-Identifier: GPL-2.0-or-later
// The outside of a mesh body, as the browser viewer draws it: triangles over
// each face on the boundary (every face of a plane element; the faces of
// solid elements that no other element shares) and the element edges on
// them. A quadratic face (CPS8, C3D20) is cut at its mid-edge nodes, so a
// magnified deformation bends it as the element does.
#pragma once

#include <cstdint>
#include <vector>

#include "numeric/instance.hpp"

namespace kanegen::animate {

struct Surface {
  std::vector<std::int32_t> triangles;  ///< node indices (FlexibleData::nodes), three per triangle
  std::vector<std::int32_t> edges;      ///< node indices, two per segment, each segment once
};

/// The surface of a mesh body's CPS4, CPS8, C3D8 and C3D20 elements
/// (elements of other types are left out, as in the VTK frames).
Surface mesh_surface(const numeric::FlexibleData& mesh);

}  // namespace kanegen::animate
