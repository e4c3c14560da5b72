// SPDX-License-Identifier: GPL-2.0-or-later
// What a rigid part is drawn as, in its body frame: a URDF link's <visual>
// shapes (box, cylinder, sphere, each placed by its <origin>), or, for a
// body without them (every body of a kanegen JSON model), the box of equal
// mass and principal moments (equivalent_box). A <visual> mesh is drawn as
// that box, with a note: kanegen reads no mesh files.
#pragma once

#include <string>
#include <vector>

#include "numeric/instance.hpp"

namespace kanegen::animate {

struct Shape {
  std::string kind;  ///< "box", "cylinder", "sphere" (a URDF <visual>) or "inertia" (the equivalent box)
  std::string name;  ///< the <visual name="..."> (untrusted text), or ""
  std::vector<numeric::Vec<double>> points;  ///< body frame
  /// The faces, each a polygon of 3 or more point indices, counter-clockwise seen from outside
  /// (a box's six too; `hexahedron` says its 8 points are also one VTK hexahedron).
  std::vector<std::vector<int>> faces;
  bool hexahedron = false;  ///< 8 points in VTK's hexahedron order
};

/// Sides of a cylinder's and meridians of a sphere's polygon; a sphere has
/// sphere_rings rings of latitude between its poles.
inline constexpr int shape_sides = 24;
inline constexpr int sphere_rings = 11;

/// A box of sides `size` centred on the origin, as a hexahedron.
Shape box_shape(const numeric::Vec<double>& size);
/// A cylinder about z (URDF's), centred on the origin: its two rims (bottom, z = -length/2, first),
/// the sides as quads and the two caps as polygons.
Shape cylinder_shape(double radius, double length);
/// A sphere centred on the origin: its south pole, its rings from south to north, its north pole.
Shape sphere_shape(double radius);

/// Per body of `instance`, what its rigid part is drawn as: where `model_path` is a URDF, the shapes
/// of its link's <visual> elements, else (and for a link without them) the equivalent box if it has
/// mass and inertia. A mesh is drawn as the equivalent box, with a note on stderr.
std::vector<std::vector<Shape>> body_shapes(const numeric::Instance& instance, const std::string& model_path);

}  // namespace kanegen::animate
