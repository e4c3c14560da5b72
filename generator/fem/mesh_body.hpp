// SPDX-License-Identifier: GPL-2.0-or-later
// A flexible body from a .inp mesh (issue 18): the continuum elements of the
// mesh (or of one element set), with the material and thickness that the
// kanegen model gives, assembled into a fem::Body in the link frame (the
// mesh's coordinates). Mesh errors (inverted elements, a missing set) become
// model::ModelErrors naming the file, line and element.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/continuum_element.hpp"
#include "fem/inp_mesh.hpp"

namespace kanegen::fem {

struct MeshBody {
  explicit MeshBody(const DofLayout& layout) : body(layout) {}

  Body body;                     ///< plane_layout or solid_layout
  std::vector<int> node_ids;     ///< body node -> mesh node id, ascending
  std::map<int, int> node_of;    ///< mesh node id -> body node
  std::vector<int> element_ids;  ///< body element -> mesh element id, file order

  /// The body dofs (every component) of the nodes of the mesh's node set `name`.
  std::vector<int> node_set_dofs(const InpMesh& mesh, const std::string& name) const;
  /// The body with every dof of the node set held at zero (a clamped face).
  Constraint clamped(const InpMesh& mesh, const std::string& node_set) const;
};

/// Builds the body from the elements of `element_set` (empty: every element of
/// the mesh's highest dimension, so the faces Gmsh writes for physical
/// surfaces are left out). Body nodes are the nodes those elements use, by
/// ascending id. thickness: for plane elements (m).
MeshBody build_mesh_body(const InpMesh& mesh, const ContinuumMaterial& material, double thickness = 1.0,
                         const std::string& element_set = "");

}  // namespace kanegen::fem
