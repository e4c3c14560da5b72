// SPDX-License-Identifier: GPL-2.0-or-later
// mesh_surface (animate/surface.hpp): the outside of a mesh body as the
// browser viewer draws it, counted by hand for small meshes.
#include "animate/surface.hpp"

#include <catch2/catch.hpp>
#include <set>
#include <utility>

using kanegen::animate::mesh_surface;
using kanegen::numeric::FlexibleData;
using kanegen::numeric::SolidElementData;

namespace {

SolidElementData element(const char* type, std::vector<int> nodes) {
  SolidElementData e;
  e.type = type;
  e.nodes = std::move(nodes);
  return e;
}

/// Two C3D8 bricks side by side along x: nodes 0-11 on a 3 x 2 x 2 grid.
FlexibleData two_bricks() {
  FlexibleData f;
  f.mesh = true;
  const auto n = [](int i, int j, int k) { return i + 3 * j + 6 * k; };
  for (int i = 0; i < 2; ++i)
    f.solids.push_back(element("C3D8", {n(i, 0, 0), n(i + 1, 0, 0), n(i + 1, 1, 0), n(i, 1, 0), n(i, 0, 1),
                                        n(i + 1, 0, 1), n(i + 1, 1, 1), n(i, 1, 1)}));
  return f;
}

}  // namespace

TEST_CASE("mesh_surface: the face two bricks share is not drawn") {
  const auto s = mesh_surface(two_bricks());
  CHECK(s.triangles.size() == 3 * 2 * 10);  // 12 faces less the shared one on each side, two triangles each
  // Edges on the outside: 20 distinct ones (12 + 12 of the bricks less the 4 of the shared face).
  CHECK(s.edges.size() == 2 * 20);
  std::set<int> used(s.triangles.begin(), s.triangles.end());
  CHECK(used.size() == 12);                                  // every node is on the outside
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) {  // no triangle of the shared face x = 1
    const int x0 = s.triangles[t] % 3, x1 = s.triangles[t + 1] % 3, x2 = s.triangles[t + 2] % 3;
    CHECK_FALSE((x0 == 1 && x1 == 1 && x2 == 1));
  }
}

TEST_CASE("mesh_surface: a plane element is drawn whole, a quadratic face cut at its mid-edge nodes") {
  FlexibleData f;
  f.mesh = true;
  f.solids.push_back(element("CPS4", {0, 1, 2, 3}));
  f.solids.push_back(element("CPS8", {1, 4, 5, 2, 6, 7, 8, 9}));
  f.solids.push_back(element("S4", {0, 1, 2, 3}));  // not drawn
  const auto s = mesh_surface(f);
  CHECK(s.triangles.size() == 3 * (2 + 6));
  CHECK(s.edges.size() == 2 * (4 + 8));  // CPS4's edge 1-2 is not CPS8's 2-9-1: none shared
}
