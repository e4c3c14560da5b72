// SPDX-License-Identifier: GPL-2.0-or-later
// What one frame of an animation shows, as points and cells (VTK's
// unstructured-grid vocabulary), from the numeric path's world poses
// (numeric/poses.hpp) at the frame's coordinates:
//  - each body's frame origin, a vertex carrying the world direction of the
//    axis of the joint that moves it (a glyph in ParaView);
//  - each rigid part as its shapes (animate/shapes.hpp): a URDF link's
//    <visual> boxes, cylinders and spheres, else, with mass, the box of equal
//    mass and principal moments (sides sqrt(6 (I_j + I_k - I_i) / m) along
//    its principal axes, about its centre of mass);
//  - each beam as a polyline through its displaced nodes;
//  - each mesh body as its elements, deformed.
// Elastic displacements are drawn magnified by `scale` and carried unscaled
// as point data.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "animate/shapes.hpp"
#include "numeric/instance.hpp"
#include "numeric/poses.hpp"

namespace kanegen::animate {

/// VTK cell types (vtkCellType.h) used here.
enum class CellType : std::uint8_t {
  vertex = 1,
  poly_line = 4,
  triangle = 5,
  polygon = 7,
  quad = 9,
  tetra = 10,
  hexahedron = 12,
  wedge = 13,
  quadratic_quad = 23,
  quadratic_tetra = 24,
  quadratic_hexahedron = 25,
  quadratic_wedge = 26,
};

/// What a point is: a body frame's origin, a point of a rigid part's shape
/// (a box's corner, a cylinder's rim, a sphere's), or a node of a beam or a mesh.
enum class PointKind : std::int32_t { frame_origin = 0, shape_point = 1, elastic_node = 2 };

struct Scene {
  std::vector<std::array<double, 3>> points;        ///< world
  std::vector<std::array<double, 3>> displacement;  ///< elastic displacement, world axes, unscaled
  std::vector<std::array<double, 3>> joint_axis;    ///< at frame origins: the joint's axis, world; else 0
  std::vector<std::int32_t> point_body;             ///< Instance::bodies index
  std::vector<std::int32_t> point_kind;             ///< PointKind
  struct Cell {
    CellType type;
    std::vector<std::int32_t> points;
    std::int32_t body;
  };
  std::vector<Cell> cells;
};

/// What places a frame's drawing, at the kernels' coordinates q (as a run's
/// CSV has them: a spherical joint's quaternion, numeric/spherical.hpp): each body's world pose
/// and, per flexible body, each node's elastic displacement (body frame,
/// unscaled; a beam's with its foreshortening under geometric stiffening in
/// modes, a mesh's with its second-order part).
struct BodyStates {
  std::vector<numeric::Pose<double>> poses;
  std::vector<std::vector<numeric::Vec<double>>> node_moves;  ///< per body; empty for a rigid one
};
BodyStates body_states(const numeric::Instance& instance, const std::vector<double>& kernel_q);

/// The box of a rigid part: its mass and principal moments about its centre
/// of mass (sides sqrt(6 (I_j + I_k - I_i) / m) along its principal axes),
/// corners in the body frame in VTK's hexahedron order; `drawn` false (no
/// box) without mass or inertia.
std::array<std::array<double, 3>, 8> equivalent_box(const numeric::BodyData& body, bool* drawn);

/// The VTK cell of a CalculiX element type and its points as indices into
/// the element's nodes (empty: CalculiX's order), from the family's row in
/// fem/element_families.cpp; false for a type without one (the element is
/// then left out of the picture).
bool vtk_cell_of(const std::string& calculix_type, CellType* type, std::vector<int>* order);

class SceneBuilder {
 public:
  /// `scale` magnifies the elastic displacements drawn; `shapes`, per body, its rigid part's
  /// (body_shapes).
  SceneBuilder(const numeric::Instance& instance, double scale, std::vector<std::vector<Shape>> shapes);

  /// The scene at the kernels' coordinates q (as a run's CSV has them: a
  /// spherical joint's quaternion, numeric/spherical.hpp).
  Scene at(const std::vector<double>& kernel_q) const;

 private:
  void add_rigid(Scene& scene, int body, const numeric::Pose<double>& pose) const;
  void add_elastic(Scene& scene, int body, const numeric::Pose<double>& pose,
                   const std::vector<numeric::Vec<double>>& moves) const;

  const numeric::Instance& instance_;
  double scale_;
  std::vector<std::vector<Shape>> shapes_;  ///< per body
};

}  // namespace kanegen::animate
