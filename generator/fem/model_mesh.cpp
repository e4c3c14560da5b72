// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/model_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "fem/ccx_matrices.hpp"
#include "fem/continuum_foreshortening.hpp"
#include "fem/craig_bampton.hpp"
#include "fem/reduction.hpp"
#include "fem/sparse_assembly.hpp"
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

/// x in 7 significant digits, for messages.
std::string shortest(double x) {
  std::ostringstream out;
  out.precision(7);
  out << x;
  return out.str();
}

/// The body dof of each row of the imported matrices: a ModelError naming the
/// .dof file and line for a node that is on none of the body's elements or a
/// direction the body lacks, and one naming a body dof the files miss that
/// the constraint does not hold (the solver's *BOUNDARY must be the body's).
std::vector<int> imported_dofs(const model::Body& body, const InpMesh& mesh, const MeshBody& mb,
                               const Constraint& constraint, const std::string& model_file) {
  const model::MeshMatrices& x = body.elastic.mesh.matrices;
  const std::string place = x.where + "/dofs";
  const std::vector<CcxDof> dofs = at_model_place(model_file, place, [&] { return read_ccx_dofs(x.dofs); });
  const Body& b = mb.body;
  std::vector<int> to_body;
  std::vector<char> listed(static_cast<std::size_t>(b.num_dofs()), 0);
  const std::string fix = "write the matrices from the same mesh and element set that \"mesh\" names";
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const std::string at = x.dofs + ": line " + std::to_string(k + 1) + ": ";
    const auto it = mb.node_of.find(dofs[k].node);
    if (it == mb.node_of.end())
      throw ModelError(
          model_file, place,
          at + "node " + std::to_string(dofs[k].node) + " is on none of the body's elements in " + mesh.file,
          fix);
    if (b.dof(it->second, static_cast<DofKind>(dofs[k].direction - 1)) < 0)
      throw ModelError(model_file, place,
                       at + "direction " + std::to_string(dofs[k].direction) + " of node " +
                           std::to_string(dofs[k].node) + ": the body's plane elements move in x and y only",
                       "import the matrices of a solid mesh (C3D8, C3D20): for a plane mesh CalculiX writes "
                       "the z rows of its 3-D expansion; leave \"matrices\" out and kanegen assembles the "
                       "plane mesh");
    to_body.push_back(b.dof(it->second, static_cast<DofKind>(dofs[k].direction - 1)));
    listed[static_cast<std::size_t>(to_body.back())] = 1;
  }
  for (int d = 0; d < b.num_dofs(); ++d)
    if (!listed[static_cast<std::size_t>(d)] && constraint.reduced_index(d) >= 0)
      throw ModelError(model_file, place,
                       x.dofs + " lists no row for node " +
                           std::to_string(mb.node_ids[d / b.dofs_per_node()]) + " direction " +
                           std::to_string(d % b.dofs_per_node() + 1) +
                           ", which the body does not hold (only the clamped set's dofs may be missing)",
                       "hold the same nodes in the CalculiX job (*BOUNDARY on the clamped set, or none) "
                       "as \"clamped_set\" (or \"support\": \"free\") does");
  return to_body;
}

/// a (n x n, the files' rows) placed at the body dofs `to_body`.
Eigen::SparseMatrix<double> to_body_dofs(const Eigen::SparseMatrix<double>& a,
                                         const std::vector<int>& to_body, int num_dofs) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < a.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it)
      triplets.emplace_back(to_body[static_cast<std::size_t>(it.row())], to_body[static_cast<std::size_t>(j)],
                            it.value());
  Eigen::SparseMatrix<double> out(num_dofs, num_dofs);
  out.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

/// The imported mass must be the mesh's consistent mass (at the dofs the files
/// list), since the inertia invariants are integrated over the mesh's
/// elements with the model's density: a ModelError naming the .mas file, the
/// largest difference and the masses otherwise.
void check_imported_mass(const model::Body& body, const MeshBody& mb, const Eigen::SparseMatrix<double>& mass,
                         const std::vector<int>& to_body, const std::string& model_file) {
  const model::MeshMatrices& x = body.elastic.mesh.matrices;
  const Body& b = mb.body;
  std::vector<char> listed(static_cast<std::size_t>(b.num_dofs()), 0);
  for (int d : to_body) listed[static_cast<std::size_t>(d)] = 1;
  // Sparse throughout: a large mesh's M does not fit densely.
  const Eigen::SparseMatrix<double> own = sparse_mass(b);
  std::vector<Eigen::Triplet<double>> kept;
  double scale = 0.0;
  for (int j = 0; j < own.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(own, j); it; ++it)
      if (listed[static_cast<std::size_t>(it.row())] && listed[static_cast<std::size_t>(j)]) {
        kept.emplace_back(static_cast<int>(it.row()), j, it.value());
        if (it.row() == j) scale = std::max(scale, std::abs(it.value()));
      }
  Eigen::SparseMatrix<double> listed_own(b.num_dofs(), b.num_dofs());
  listed_own.setFromTriplets(kept.begin(), kept.end());
  const Eigen::SparseMatrix<double> difference = mass - listed_own;
  double worst = 0.0;
  for (int j = 0; j < difference.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(difference, j); it; ++it)
      worst = std::max(worst, std::abs(it.value()));
  // The x translations' sums: the mass the listed dofs carry, for the message.
  Eigen::VectorXd x_dofs = Eigen::VectorXd::Zero(b.num_dofs());
  for (int d : to_body)
    if (d % b.dofs_per_node() == 0) x_dofs(d) = 1.0;
  const double own_x = x_dofs.dot(listed_own * x_dofs), imported_x = x_dofs.dot(mass * x_dofs);
  if (!(scale > 0.0))
    throw ModelError(model_file, x.where + "/mass",
                     "the mesh's elements have no mass at the dofs of " + x.dofs,
                     "give the material a positive \"density\"");
  if (worst > 1e-6 * scale)
    throw ModelError(
        model_file, x.where + "/mass",
        x.mass + " is not the consistent mass of the mesh with density " + shortest(body.elastic.density) +
            " kg/m^3: entries differ by up to " + shortest(worst / scale) +
            " of the largest diagonal (its x translations sum to " + shortest(imported_x) +
            " kg, the mesh's to " + shortest(own_x) + " kg); the inertia invariants are the mesh's",
        "give the model the CalculiX job's *DENSITY, and write the matrices with full-integration "
        "elements of the same mesh (a lumped mass matrix is not accepted)");
}

/// num_dofs x 6: the body's rigid motions, translations along and rotations
/// about x, y, z through the nodes' centroid (a plane body's rotations about
/// x and y are zero columns: they move out of its plane only).
Eigen::MatrixXd rigid_motions(const Body& b) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int node = 0; node < b.num_nodes(); ++node) c += b.node_position(node);
  c /= static_cast<double>(b.num_nodes());
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(b.num_dofs(), 6);
  const DofKind kinds[3] = {DofKind::kUx, DofKind::kUy, DofKind::kUz};
  for (int node = 0; node < b.num_nodes(); ++node) {
    const Eigen::Vector3d p = b.node_position(node) - c;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d turn = Eigen::Vector3d::Unit(a).cross(p);
      for (int k = 0; k < 3; ++k) {
        const int d = b.dof(node, kinds[k]);
        if (d < 0) continue;
        r(d, a) = a == k ? 1.0 : 0.0;
        r(d, 3 + a) = turn(k);
      }
    }
  }
  return r;
}

/// A body's K leaves its rigid motions unstrained: (K r)_d = 0 at every dof d
/// that couples (in the mesh's own K) to listed dofs only. A line of the .sti
/// file missing or changed breaks that: a ModelError naming the file and the
/// node otherwise. Called before the import (the mesh's own K).
void check_imported_stiffness(const model::Body& body, const MeshBody& mb,
                              const Eigen::SparseMatrix<double>& k, const std::vector<int>& to_body,
                              const std::string& model_file) {
  const model::MeshMatrices& x = body.elastic.mesh.matrices;
  const Body& b = mb.body;
  std::vector<char> listed(static_cast<std::size_t>(b.num_dofs()), 0);
  for (int d : to_body) listed[static_cast<std::size_t>(d)] = 1;
  std::vector<char> inner = listed;
  const Eigen::SparseMatrix<double> own = sparse_stiffness(b);
  for (int j = 0; j < own.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(own, j); it; ++it)
      if (!listed[static_cast<std::size_t>(j)]) inner[static_cast<std::size_t>(it.row())] = 0;
  const Eigen::MatrixXd r = rigid_motions(b);
  const Eigen::MatrixXd kr = k * r;
  const Eigen::MatrixXd scale = Eigen::SparseMatrix<double>(k.cwiseAbs()) * r.cwiseAbs();
  const char* motion[6] = {"translation along x", "translation along y", "translation along z",
                           "rotation about x",    "rotation about y",    "rotation about z"};
  for (int d = 0; d < b.num_dofs(); ++d)
    for (int c = 0; c < 6; ++c)
      if (inner[static_cast<std::size_t>(d)] && std::abs(kr(d, c)) > 1e-8 * scale(d, c))
        throw ModelError(model_file, x.where + "/stiffness",
                         x.stiffness + " strains the body's rigid " + motion[c] + " at node " +
                             std::to_string(mb.node_ids[static_cast<std::size_t>(d / b.dofs_per_node())]) +
                             " direction " + std::to_string(d % b.dofs_per_node() + 1) + ": K r is " +
                             shortest(std::abs(kr(d, c)) / scale(d, c)) +
                             " of |K| |r| there, where a stiffness gives 0 (a line missing or changed?)",
                         "give the complete .sti file CalculiX wrote for this mesh, unchanged");
}

/// Replaces K and M of the body by the solver's files (model::MeshMatrices).
void import_matrices(const model::Body& body, const InpMesh& mesh, const Constraint& constraint, MeshBody& mb,
                     const std::string& model_file) {
  const model::MeshMatrices& x = body.elastic.mesh.matrices;
  const std::vector<int> to_body = imported_dofs(body, mesh, mb, constraint, model_file);
  const int n = static_cast<int>(to_body.size()), num_dofs = mb.body.num_dofs();
  const Eigen::SparseMatrix<double> k = at_model_place(model_file, x.where + "/stiffness", [&] {
    return to_body_dofs(read_ccx_matrix(x.stiffness, n), to_body, num_dofs);
  });
  const Eigen::SparseMatrix<double> m = at_model_place(model_file, x.where + "/mass", [&] {
    return to_body_dofs(read_ccx_matrix(x.mass, n), to_body, num_dofs);
  });
  check_imported_stiffness(body, mb, k, to_body, model_file);
  check_imported_mass(body, mb, m, to_body, model_file);
  mb.body.set_imported_matrices(k, m);
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
  MeshBody mb = build_model_mesh_body(body, mesh, model_file);
  const Constraint constraint = f.support == model::BeamSupport::free
                                    ? Constraint(mb.body.num_dofs(), {})
                                    : at_model_place(model_file, f.mesh.where + "/clamped_set",
                                                     [&] { return mb.clamped(mesh, f.mesh.clamped_set); });
  if (f.mesh.matrices.present()) import_matrices(body, mesh, constraint, mb, model_file);
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
