// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/mesh_body.hpp"

#include <algorithm>
#include <memory>
#include <set>
#include <sstream>

#include "model/model_error.hpp"

namespace kanegen::fem {

namespace {

using model::ModelError;

std::string place(const MeshElement& e) {
  return "line " + std::to_string(e.line) + ", element " + std::to_string(e.id);
}

}  // namespace

std::vector<int> MeshBody::node_set_dofs(const InpMesh& mesh, const std::string& name) const {
  std::vector<int> dofs;
  for (int id : mesh.node_set(name)) {
    const auto it = node_of.find(id);
    if (it == node_of.end())
      throw ModelError(mesh.file, "node set " + name,
                       "node " + std::to_string(id) + " of the set is on none of the body's elements",
                       "put only nodes of the body's elements in the set");
    for (int k = 0; k < body.dofs_per_node(); ++k) dofs.push_back(body.dof(it->second, k));
  }
  return dofs;
}

Constraint MeshBody::clamped(const InpMesh& mesh, const std::string& node_set) const {
  return Constraint(body.num_dofs(), node_set_dofs(mesh, node_set));
}

MeshBody build_mesh_body(const InpMesh& mesh, const ContinuumMaterial& material, double thickness,
                         const std::string& element_set) {
  std::vector<const MeshElement*> chosen;
  if (element_set.empty()) {
    int dimension = 0;
    for (const MeshElement& e : mesh.elements) dimension = std::max(dimension, family_dimension(e.family));
    for (const MeshElement& e : mesh.elements)
      if (family_dimension(e.family) == dimension) chosen.push_back(&e);
  } else {
    const std::vector<int>& ids = mesh.element_set(element_set);
    for (const MeshElement& e : mesh.elements)
      if (std::binary_search(ids.begin(), ids.end(), e.id)) chosen.push_back(&e);
    if (chosen.empty())
      throw ModelError(mesh.file, "element set " + element_set, "the element set is empty",
                       "list the body's elements in it");
    for (const MeshElement* e : chosen)
      if (family_dimension(e->family) != family_dimension(chosen.front()->family))
        throw ModelError(mesh.file, place(*e),
                         "element set " + element_set + " mixes plane and solid elements",
                         "make the body of plane elements only or of solid elements only");
  }
  const bool plane = family_dimension(chosen.front()->family) == 2;
  MeshBody out(plane ? plane_layout() : solid_layout());
  std::set<int> used;
  for (const MeshElement* e : chosen) used.insert(e->nodes.begin(), e->nodes.end());
  for (int id : used) {
    out.node_of[id] = out.body.add_node(mesh.nodes[mesh.node_index(id)].position);
    out.node_ids.push_back(id);
  }
  for (const MeshElement* e : chosen) {
    Eigen::Matrix3Xd x(3, e->nodes.size());
    std::vector<int> body_nodes;
    for (std::size_t i = 0; i < e->nodes.size(); ++i) {
      body_nodes.push_back(out.node_of.at(e->nodes[i]));
      x.col(static_cast<int>(i)) = out.body.node_position(body_nodes.back());
    }
    std::shared_ptr<ContinuumElement> element;
    try {
      element = std::make_shared<ContinuumElement>(e->family, x, material, thickness);
    } catch (const InvertedElementError& error) {
      std::ostringstream problem;
      problem << ccx_type_name(e->family) << " element " << e->id << " is inverted or folded ("
              << error.what() << ")";
      throw ModelError(mesh.file, place(*e), problem.str(),
                       plane ? "number its corners counter-clockwise seen from +z, then the mid-edge nodes"
                             : "number the corners of one face counter-clockwise seen from the opposite "
                               "face, then that face's corners in the same order, then the mid-edge nodes");
    } catch (const std::invalid_argument& error) {
      throw ModelError(mesh.file, place(*e), error.what(), "check the element's nodes and the material");
    }
    out.body.add_element(element, body_nodes, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    out.element_ids.push_back(e->id);
  }
  return out;
}

}  // namespace kanegen::fem
