// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/surface.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <utility>

namespace kanegen::animate {
namespace {

/// A face of an element: four corners in turn, and the node in the middle
/// of each edge corner[k] - corner[k + 1] (-1 for a linear element).
/// Indices are into the element's node list, CalculiX's order.
struct Face {
  std::array<int, 4> corner, middle;
};

/// The faces of a CalculiX element type, or none for a type not drawn.
std::vector<Face> faces_of(const std::string& type) {
  static const std::array<int, 4> linear{-1, -1, -1, -1};
  if (type == "CPS4") return {{{0, 1, 2, 3}, linear}};
  if (type == "CPS8") return {{{0, 1, 2, 3}, {4, 5, 6, 7}}};
  // Solids: bottom, top, then the four sides; C3D20's mid-edge nodes 8-19
  // lie on edges 0-1, 1-2, 2-3, 3-0, 4-5, 5-6, 6-7, 7-4, 0-4, 1-5, 2-6, 3-7.
  static const std::array<std::array<int, 4>, 6> corners{
      {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}}};
  static const std::array<std::array<int, 4>, 6> middles{{{8, 9, 10, 11},
                                                          {15, 14, 13, 12},
                                                          {16, 12, 17, 8},
                                                          {17, 13, 18, 9},
                                                          {18, 14, 19, 10},
                                                          {19, 15, 16, 11}}};
  std::vector<Face> faces;
  if (type == "C3D8" || type == "C3D20")
    for (int f = 0; f < 6; ++f) faces.push_back({corners[f], type == "C3D20" ? middles[f] : linear});
  return faces;
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
  if (m[0] < 0) {
    s.triangles.insert(s.triangles.end(), {c[0], c[1], c[2], c[0], c[2], c[3]});
    for (int k = 0; k < 4; ++k) edge(c[k], c[(k + 1) % 4]);
    return;
  }
  // A corner triangle at each corner, and the inner quad of the mid-edge nodes as two.
  s.triangles.insert(s.triangles.end(), {c[0], m[0], m[3], m[0], c[1], m[1], m[1], c[2], m[2], m[2], c[3],
                                         m[3], m[0], m[1], m[2], m[0], m[2], m[3]});
  for (int k = 0; k < 4; ++k) {
    edge(c[k], m[k]);
    edge(m[k], c[(k + 1) % 4]);
  }
}

}  // namespace

Surface mesh_surface(const numeric::FlexibleData& mesh) {
  // A solid's face is on the boundary when no other element has the same corners.
  std::map<std::array<int, 4>, std::pair<int, PlacedFace>> solid_faces;
  std::vector<PlacedFace> plane_faces;
  for (const numeric::SolidElementData& e : mesh.solids)
    for (const Face& face : faces_of(e.type)) {
      PlacedFace placed{};
      for (int k = 0; k < 4; ++k) {
        placed.corner[k] = e.nodes[face.corner[k]];
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
