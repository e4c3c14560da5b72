// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/surface.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "fem/element_families.hpp"

namespace kanegen::animate {
namespace {

/// The faces of a CalculiX element type (its family's row,
/// fem/element_families.cpp), or none for a type not drawn.
std::vector<fem::FamilyFace> faces_of(const std::string& type) {
  fem::ContinuumFamily family;
  if (!fem::family_from_ccx_name(type, family)) return {};
  return fem::family_row(family).faces;
}

/// A face with its element's node numbers (FlexibleData indices).
struct PlacedFace {
  std::array<int, 4> corner, middle;
};

void add_face(Surface& s, std::set<std::pair<int, int>>& edges, const PlacedFace& f) {
  const auto& c = f.corner;
  const auto& m = f.middle;
  const auto edge = [&](int a, int b) {
    if (edges.insert({std::min(a, b), std::max(a, b)}).second) s.edges.insert(s.edges.end(), {a, b});
  };
  const int n = c[3] < 0 ? 3 : 4;  // a triangle or a quadrilateral
  if (m[0] < 0) {
    s.triangles.insert(s.triangles.end(), {c[0], c[1], c[2]});
    if (n == 4) s.triangles.insert(s.triangles.end(), {c[0], c[2], c[3]});
    for (int k = 0; k < n; ++k) edge(c[k], c[(k + 1) % n]);
    return;
  }
  // A corner triangle at each corner, and the inner polygon of the mid-edge nodes.
  s.triangles.insert(s.triangles.end(), {c[0], m[0], m[n - 1]});
  for (int k = 1; k < n; ++k) s.triangles.insert(s.triangles.end(), {m[k - 1], c[k], m[k]});
  s.triangles.insert(s.triangles.end(), {m[0], m[1], m[2]});
  if (n == 4) s.triangles.insert(s.triangles.end(), {m[0], m[2], m[3]});
  for (int k = 0; k < n; ++k) {
    edge(c[k], m[k]);
    edge(m[k], c[(k + 1) % n]);
  }
}

}  // namespace

Surface mesh_surface(const numeric::FlexibleData& mesh) {
  // A solid's face is on the boundary when no other element has the same corners.
  std::map<std::array<int, 4>, std::pair<int, PlacedFace>> solid_faces;
  std::vector<PlacedFace> plane_faces;
  for (const numeric::SolidElementData& e : mesh.solids)
    for (const fem::FamilyFace& face : faces_of(e.type)) {
      PlacedFace placed{};
      for (int k = 0; k < 4; ++k) {
        placed.corner[k] = face.corner[k] < 0 ? -1 : e.nodes[face.corner[k]];
        placed.middle[k] = face.middle[k] < 0 ? -1 : e.nodes[face.middle[k]];
      }
      if (e.type.rfind("CPS", 0) == 0) {
        plane_faces.push_back(placed);
        continue;
      }
      std::array<int, 4> key = placed.corner;
      std::sort(key.begin(), key.end());
      const auto it = solid_faces.insert({key, {0, placed}}).first;
      ++it->second.first;
    }
  Surface surface;
  std::set<std::pair<int, int>> edges;
  for (const PlacedFace& f : plane_faces) add_face(surface, edges, f);
  for (const auto& [key, counted] : solid_faces)
    if (counted.first == 1) add_face(surface, edges, counted.second);
  return surface;
}

}  // namespace kanegen::animate
