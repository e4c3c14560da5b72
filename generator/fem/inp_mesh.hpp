// SPDX-License-Identifier: GPL-2.0-or-later
// A CalculiX / Abaqus .inp mesh (issue 18): nodes, continuum elements, node
// and element sets, as CalculiX or Gmsh (`gmsh -3 -format inp`) writes them.
// The material comes from the kanegen model, so keywords other than *NODE,
// *ELEMENT, *NSET and *ELSET (*MATERIAL, *STEP, *HEADING...) are skipped with
// their data lines. Every error is a model::ModelError naming the file, the
// line and the node, element or set, with the fix.
#pragma once

#include <Eigen/Dense>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "fem/continuum_element.hpp"

namespace kanegen::fem {

struct MeshNode {
  int id = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int line = 0;
};

struct MeshElement {
  int id = 0;
  ContinuumFamily family = ContinuumFamily::kHex8;
  std::vector<int> nodes;  ///< node ids, CalculiX order
  int line = 0;            ///< the line its record starts on
};

struct InpMesh {
  std::string file;  ///< as given to the reader, for messages
  std::vector<MeshNode> nodes;
  std::vector<MeshElement> elements;
  /// Sets by upper-case name (names are case-insensitive in .inp), ids ascending, no repeats.
  std::map<std::string, std::vector<int>> node_sets, element_sets;

  /// Index into `nodes` of a node id, or -1.
  int node_index(int id) const;
  /// The node set's ids; a ModelError naming the file and the sets it has if there is none.
  const std::vector<int>& node_set(const std::string& name) const;
  const std::vector<int>& element_set(const std::string& name) const;

  std::map<int, int> node_index_of_id;  ///< id -> index in nodes (filled by the reader)
};

/// Reads a .inp mesh; `file` names it in messages. Element types: CPS4, CPS8,
/// C3D8, C3D20 (CPS4R, CPS8R, C3D8R, C3D20R and CPE*/CAX* are refused: their
/// integration or kinematics differ from what the elements here compute).
InpMesh read_inp_mesh(std::istream& in, const std::string& file);
InpMesh read_inp_mesh_file(const std::string& path);

}  // namespace kanegen::fem
