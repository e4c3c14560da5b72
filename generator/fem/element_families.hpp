// SPDX-License-Identifier: GPL-2.0-or-later
// The continuum element families, one row each: CalculiX / Abaqus name,
// dimension, nodes with their natural coordinates, shape functions and the
// quadrature that K_e, K_sigma and the mass use. Everything else about an
// element (ContinuumElement, the .inp reader, the mesh body) reads a family
// through this table, so a new family is an enum value and a row here plus
// its independent twin in numeric/solid.hpp (docs/architecture.md#adding-an-element).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

namespace kanegen::fem {

enum class ContinuumFamily { kQuad4, kQuad8, kHex8, kHex20, kTet10, kWedge6, kWedge15 };

/// Shape functions N (num_nodes) and their derivatives dN/dxi (num_nodes x dimension) at xi.
struct NaturalShape {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
};

/// A quadrature point: natural coordinates and weight (natural measure).
struct NaturalPoint {
  Eigen::Vector3d xi;
  double weight;
};

/// A face of an element as `kanegen animate` draws it: its corners in turn
/// (outward normal by the right-hand rule; corner[3] = -1 for a triangle)
/// and the node in the middle of each edge corner[k] - corner[k + 1] (-1 for
/// a linear element). Indices into the element's nodes, CalculiX order.
struct FamilyFace {
  std::array<int, 4> corner, middle;
};

struct FamilyRow {
  ContinuumFamily family;
  const char* ccx_name;  ///< CalculiX / Abaqus *ELEMENT TYPE
  int dimension;         ///< 2: plane stress (thickness t), 3: solid
  int nodes;
  /// dimension x nodes: the nodes' natural coordinates, CalculiX order.
  Eigen::MatrixXd (*natural_nodes)();
  NaturalShape (*shape)(const Eigen::Vector3d& xi);
  /// The points of K_e, K_sigma and the mass, each weight multiplied into
  /// `scale` (the thickness of plane elements, else 1), so that the products
  /// are formed in one fixed order (the generated code prints them).
  std::vector<NaturalPoint> (*quadrature)(double scale);
  /// The VTK cell type number (.vtu files of `kanegen animate`).
  int vtk_cell;
  /// The VTK cell's points as indices into the CalculiX nodes; empty: the
  /// same order as CalculiX's.
  std::vector<int> vtk_nodes;
  /// The faces `kanegen animate` draws (the outer ones of a mesh).
  std::vector<FamilyFace> faces;
};

/// The row of a family.
const FamilyRow& family_row(ContinuumFamily family);
/// The family of a CalculiX type name (upper case); false if none.
bool family_from_ccx_name(const std::string& name, ContinuumFamily& family);
/// "CPS4, CPS8, C3D8, C3D20, ...": the type names kanegen reads, for messages.
std::string supported_ccx_names();

/// CalculiX / Abaqus type name of the family: CPS4, CPS8, C3D8, C3D20, C3D10, C3D6, C3D15.
inline const char* ccx_type_name(ContinuumFamily family) { return family_row(family).ccx_name; }
inline int family_num_nodes(ContinuumFamily family) { return family_row(family).nodes; }
/// 2 for the plane-stress quadrilaterals, 3 for the solids.
inline int family_dimension(ContinuumFamily family) { return family_row(family).dimension; }
/// dimension x num_nodes: the nodes' natural coordinates, CalculiX order.
inline Eigen::MatrixXd family_natural_nodes(ContinuumFamily family) {
  return family_row(family).natural_nodes();
}
inline NaturalShape natural_shape(ContinuumFamily family, const Eigen::Vector3d& xi) {
  return family_row(family).shape(xi);
}

}  // namespace kanegen::fem
