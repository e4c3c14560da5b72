// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/model_mesh.hpp"

#include <fstream>
#include <stdexcept>

#include "fem/continuum_foreshortening.hpp"
#include "fem/craig_bampton.hpp"
#include "fem/reduction.hpp"
#include "model/model_error.hpp"

namespace kanegen::fem {

namespace {

using model::ModelError;

/// Reruns `f`, turning a mesh-layer error (it names the mesh file) into one
/// that names the model's place as well.
template <class F>
auto at_model_place(const std::string& model_file, const std::string& place, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const ModelError& e) {
    throw ModelError(model_file, place, e.what(), "");
  }
}

/// Geometric stiffening: the second-order displacement field of the body held
/// on `held` (its clamped set), and its foreshortening at each interface,
/// by the mean translation of the interface's body nodes (as interface_point
/// averages the first-order motion).
void add_foreshortening(const model::Body& body, const Constraint& held,
                        const std::vector<std::vector<int>>& interface_nodes, const std::string& model_file,
                        ElasticModel& out) {
  try {
    out.second_order = second_order_fields(out.body, held, out.reduced.basis);
  } catch (const std::invalid_argument& e) {
    throw ModelError(model_file, body.elastic.where + "/geometric_stiffening",
                     "the geometric stiffening of body '" + body.name + "' failed: " + e.what(),
                     "set \"geometric_stiffening\": false");
  }
  std::vector<Eigen::MatrixXd> points;
  for (const std::vector<int>& nodes : interface_nodes) {
    Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(3, out.body.num_dofs());
    for (int n : nodes) mean += out.body.node_translation(n);
    points.push_back(mean / static_cast<double>(nodes.size()));
  }
  out.foreshortening = continuum_foreshortening(out.body, out.second_order,
                                                static_cast<int>(out.reduced.basis.cols()), points);
  add_second_order_mass(out.body, out.reduced.basis, out.second_order, *out.foreshortening);
}

}  // namespace

InpMesh read_model_mesh(const model::Body& body, const std::string& model_file) {
  const model::MeshSource& m = body.elastic.mesh;
  if (!std::ifstream(m.path))
    throw ModelError(model_file, m.where + "/file",
                     "cannot open the mesh file '" + m.path + "' of body '" + body.name + "'",
                     "give the .inp file's path relative to the model file");
  return read_inp_mesh_file(m.path);
}

MeshBody build_model_mesh_body(const model::Body& body, const InpMesh& mesh, const std::string& model_file) {
  const model::ElasticPart& f = body.elastic;
  const ContinuumMaterial material{f.E, f.mesh.poisson, f.density};
  return at_model_place(model_file, f.mesh.where + "/element_set", [&] {
    return build_mesh_body(mesh, material, f.mesh.thickness, f.mesh.element_set);
  });
}

/// The body nodes of the interface's node set; a ModelError if the mesh
/// lacks the set, the set is empty or holds a node of no element of the body.
std::vector<int> interface_nodes(const MeshBody& mb, const InpMesh& mesh, const model::MeshInterface& in,
                                 const std::string& model_file) {
  const std::string& name = in.node_set;
  const std::string& place = in.where;
  const std::vector<int> ids = at_model_place(model_file, place, [&] { return mesh.node_set(name); });
  std::vector<int> nodes;
  for (int id : ids) {
    const auto it = mb.node_of.find(id);
    if (it == mb.node_of.end())
      throw ModelError(model_file, place,
                       mesh.file + ": node " + std::to_string(id) + " of node set " + name +
                           " is on none of the body's elements",
                       "put only nodes of the body's elements in the set");
    nodes.push_back(it->second);
  }
  if (nodes.empty())
    throw ModelError(model_file, place, "node set " + name + " of " + mesh.file + " has no nodes",
                     "list the nodes of the set in the mesh file");
  return nodes;
}

/// The averaged motion in the basis of the interface on body nodes `nodes`
/// (interface_nodes). Its rotation is left zero where it is undetermined
/// (one node; in space, nodes on one line), which is an error only if
/// something uses it (`in.rotation_where`).
InterfacePoint interface_point(const MeshBody& mb, const InpMesh& mesh, const model::MeshInterface& in,
                               const std::vector<int>& nodes, const Eigen::MatrixXd& basis,
                               const std::string& model_file) {
  const std::string& name = in.node_set;
  const Body& b = mb.body;
  const bool plane = b.dofs_per_node() == 2;
  InterfacePoint p;
  p.name = name;
  p.position.setZero();
  for (int n : nodes) p.position += b.node_position(n);
  p.position /= static_cast<double>(nodes.size());
  // Least squares: u_i ~ t + theta x r_i, r_i from the centroid: t is the
  // mean displacement, A theta = sum r_i x u_i with A = sum |r_i|^2 I - r_i r_i^T.
  // In the basis (u_i: 3 x n), the moment taking u_i - u_0 (the same, as
  // sum r_i = 0): a shape that translates the set rigidly turns it by
  // exactly 0, not by the round-off of sum r_i over a small A (1e-12 on a
  // solid's face).
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(3, basis.cols()), moment = t;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  const Eigen::MatrixXd u0 = b.node_translation(nodes.front()) * basis;
  for (int n : nodes) {
    const Eigen::Vector3d r = b.node_position(n) - p.position;
    const Eigen::MatrixXd u = b.node_translation(n) * basis;
    t += u / static_cast<double>(nodes.size());
    Eigen::Matrix3d cross;
    cross << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    moment += cross * (u - u0);
    A += r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
  }
  Eigen::MatrixXd theta = Eigen::MatrixXd::Zero(3, basis.cols());
  const std::string& turns = in.rotation_where;
  if (plane) {
    // In the plane only the rotation about z exists.
    if (A(2, 2) > 0)
      theta.row(2) = moment.row(2) / A(2, 2);
    else if (!turns.empty())
      throw ModelError(model_file, turns,
                       "node set " + name + " of " + mesh.file + " is a single node, which has no rotation",
                       "give a set of two or more nodes, so that it turns with the body");
  } else {
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
    if (ldlt.rcond() >= 1e-9 && ldlt.info() == Eigen::Success)
      theta = ldlt.solve(moment);
    else if (!turns.empty())
      throw ModelError(model_file, turns,
                       "the nodes of node set " + name + " of " + mesh.file +
                           (nodes.size() == 1 ? " are one node" : " lie on a line") +
                           ", so its rotation is undetermined",
                       "give a set of nodes on a face (not all on one line)");
  }
  p.translation = t;
  p.rotation = theta;
  return p;
}

ElasticModel build_model_mesh(const model::Body& body, const std::string& model_file) {
  const model::ElasticPart& f = body.elastic;
  const InpMesh mesh = read_model_mesh(body, model_file);
  const MeshBody mb = build_model_mesh_body(body, mesh, model_file);
  const Constraint constraint = f.support == model::BeamSupport::free
                                    ? Constraint(mb.body.num_dofs(), {})
                                    : at_model_place(model_file, f.mesh.where + "/clamped_set",
                                                     [&] { return mb.clamped(mesh, f.mesh.clamped_set); });
  if (f.modes > constraint.num_free())
    throw ModelError(model_file, f.where + "/modes",
                     "body '" + body.name + "' has " + std::to_string(constraint.num_free()) +
                         " free dofs, fewer than the " + std::to_string(f.modes) + " modes asked for",
                     "keep fewer modes, or refine the mesh");
  ElasticModel out{mb.body, {}, {}, {}, {}, {}, std::nullopt, {}, true, {}};
  std::vector<std::vector<int>> interfaces;
  for (const model::MeshInterface& in : f.mesh.interfaces)
    interfaces.push_back(interface_nodes(mb, mesh, in, model_file));
  if (f.mesh.craig_bampton) {
    try {
      const CraigBamptonBasis cb = craig_bampton(out.body, constraint, interfaces, f.modes);
      out.reduced = reduce_assumed(out.body, cb.basis);
    } catch (const std::invalid_argument& e) {
      throw ModelError(
          model_file, f.mesh.where + "/reduction",
          "Craig-Bampton reduction of body '" + body.name + "' failed: " + e.what(),
          "keep the interface node sets apart from the clamped set, with two or more nodes each, "
          "and keep fewer modes");
    }
  } else if (f.support == model::BeamSupport::free) {
    // The joint carries the rigid motions: the free-free body's first modes
    // (3 in the plane, 6 in space, omega = 0) would duplicate them.
    const int rigid = out.body.dofs_per_node() == 2 ? 3 : 6;
    if (f.modes + rigid > constraint.num_free())
      throw ModelError(
          model_file, f.where + "/modes",
          "body '" + body.name + "' has too few dofs for " + std::to_string(f.modes) + " elastic modes",
          "keep fewer modes, or refine the mesh");
    const ReducedBody all = reduce_modal(out.body, constraint, f.modes + rigid);
    out.reduced = reduce_assumed(out.body, all.basis.rightCols(f.modes));
    out.reduced.omega = all.omega.tail(f.modes);
  } else {
    out.reduced = reduce_modal(out.body, constraint, f.modes);
  }
  out.is_mesh = true;
  for (std::size_t i = 0; i < interfaces.size(); ++i)
    out.interfaces.push_back(
        interface_point(mb, mesh, f.mesh.interfaces[i], interfaces[i], out.reduced.basis, model_file));
  out.damping = reduced_damping(f, out.reduced, true);
  if (f.geometric_stiffening) add_foreshortening(body, constraint, interfaces, model_file, out);
  return out;
}

}  // namespace kanegen::fem
