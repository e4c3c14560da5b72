// SPDX-License-Identifier: GPL-2.0-or-later
// mesh_surface (animate/surface.hpp): the outside of a mesh body as the
// browser viewer draws it, counted by hand for small meshes.
#include "animate/surface.hpp"

#include <array>
#include <catch2/catch.hpp>
#include <set>
#include <utility>
#include <vector>

#include "animate/scene.hpp"

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

namespace {

/// The outward normal of triangle t of s, by the right-hand rule, at the positions x.
std::array<double, 3> normal_of(const kanegen::animate::Surface& s, std::size_t t,
                                const std::vector<std::array<double, 3>>& x) {
  const auto& a = x[s.triangles[t]];
  const auto& b = x[s.triangles[t + 1]];
  const auto& c = x[s.triangles[t + 2]];
  const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
      v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

/// Every triangle of s faces away from the point inside (its normal points from inside to the triangle).
bool all_outward(const kanegen::animate::Surface& s, const std::vector<std::array<double, 3>>& x,
                 const std::array<double, 3>& inside) {
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) {
    const auto n = normal_of(s, t, x);
    const auto& a = x[s.triangles[t]];
    if (n[0] * (a[0] - inside[0]) + n[1] * (a[1] - inside[1]) + n[2] * (a[2] - inside[2]) <= 0) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("mesh_surface: tetrahedra and wedges, their faces outward, a shared face not drawn") {
  // C3D10 with CalculiX's nodes: corners (0,0,0), (1,0,0), (0,1,0), (0,0,1), mid-edge nodes on 1-2, 2-3,
  // 3-1, 1-4, 2-4, 3-4.
  const std::vector<std::array<double, 3>> tet{{0, 0, 0},     {1, 0, 0},     {0, 1, 0},   {0, 0, 1},
                                               {0.5, 0, 0},   {0.5, 0.5, 0}, {0, 0.5, 0}, {0, 0, 0.5},
                                               {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  FlexibleData f;
  f.mesh = true;
  f.solids.push_back(element("C3D10", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  auto s = mesh_surface(f);
  CHECK(s.triangles.size() == 3 * 4 * 4);  // 4 faces cut into 4 triangles at the mid-edge nodes
  CHECK(s.edges.size() == 2 * 12);         // 6 edges, each in two halves
  CHECK(all_outward(s, tet, {0.2, 0.2, 0.2}));
  // C3D6 and C3D15 with CalculiX's nodes: the triangle (0,0), (1,0), (0,1) at z = -1, then at z = 1; the
  // C3D15's mid-edge nodes on 1-2, 2-3, 3-1, 4-5, 5-6, 6-4, 1-4, 2-5, 3-6.
  std::vector<std::array<double, 3>> wedge{{0, 0, -1}, {1, 0, -1}, {0, 1, -1},
                                           {0, 0, 1},  {1, 0, 1},  {0, 1, 1}};
  for (int k = 0; k < 9; ++k) {
    static const int ends[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
    const auto& a = wedge[ends[k][0]];
    const auto& b = wedge[ends[k][1]];
    wedge.push_back({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2});
  }
  f.solids = {element("C3D6", {0, 1, 2, 3, 4, 5})};
  s = mesh_surface(f);
  CHECK(s.triangles.size() == 3 * (2 + 3 * 2));  // two triangles, three quadrilaterals of two
  CHECK(s.edges.size() == 2 * 9);
  CHECK(all_outward(s, wedge, {0.3, 0.3, 0.0}));
  f.solids = {element("C3D15", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14})};
  s = mesh_surface(f);
  CHECK(s.triangles.size() == 3 * (2 * 4 + 3 * 6));
  CHECK(s.edges.size() == 2 * 18);
  CHECK(all_outward(s, wedge, {0.3, 0.3, 0.0}));
  // Two wedges on top of each other (the second's bottom is the first's top): that face is drawn by neither.
  for (int k = 0; k < 3; ++k) wedge.push_back({wedge[3 + k][0], wedge[3 + k][1], 3.0});
  f.solids = {element("C3D6", {0, 1, 2, 3, 4, 5}), element("C3D6", {3, 4, 5, 15, 16, 17})};
  s = mesh_surface(f);
  CHECK(s.triangles.size() == 3 * (2 + 2 * 3 * 2));
  for (std::size_t t = 0; t < s.triangles.size(); t += 3) {
    const bool middle = wedge[s.triangles[t]][2] == 1 && wedge[s.triangles[t + 1]][2] == 1 &&
                        wedge[s.triangles[t + 2]][2] == 1;
    CHECK_FALSE(middle);
  }
}

TEST_CASE("vtk_cell_of: tetrahedra and wedges as VTK's cells, in VTK's node order") {
  using kanegen::animate::CellType;
  CellType type;
  std::vector<int> order;
  REQUIRE(kanegen::animate::vtk_cell_of("C3D10", &type, &order));
  CHECK(type == CellType::quadratic_tetra);  // VTK_QUADRATIC_TETRA, CalculiX's order
  CHECK(order.empty());
  REQUIRE(kanegen::animate::vtk_cell_of("C3D6", &type, &order));
  CHECK(type == CellType::wedge);
  // VTK's wedge (vtkWedge): the triangle 0-1-2's normal by the right-hand rule points away from 3-4-5.
  // CalculiX's 1-2-3 faces towards 4-5-6: the VTK cell takes them in the order 1, 3, 2, 4, 6, 5.
  CHECK(order == std::vector<int>{0, 2, 1, 3, 5, 4});
  REQUIRE(kanegen::animate::vtk_cell_of("C3D15", &type, &order));
  CHECK(type == CellType::quadratic_wedge);
  // VTK_QUADRATIC_WEDGE: the corners as for the wedge, then the mid-edge nodes of VTK's edges 0-1, 1-2,
  // 2-0, 3-4, 4-5, 5-3, 0-3, 1-4, 2-5, which are CalculiX's edges 1-3, 3-2, 2-1, ... : its nodes 9, 8, 7,
  // 12, 11, 10, 13, 15, 14.
  CHECK(order == std::vector<int>{0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13});
  CHECK_FALSE(kanegen::animate::vtk_cell_of("C3D4", &type, &order));
}
