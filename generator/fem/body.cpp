// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/body.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace kanegen::fem {

namespace {

int kind_index(DofKind kind) { return static_cast<int>(kind); }  // 0..2 translations, 3..5 rotations

/// ndpn x 6: picks the layout's components out of (translation; rotation).
Eigen::MatrixXd selector(const DofLayout& layout) {
  Eigen::MatrixXd e = Eigen::MatrixXd::Zero(static_cast<int>(layout.size()), 6);
  for (std::size_t k = 0; k < layout.size(); ++k) e(static_cast<int>(k), kind_index(layout[k])) = 1.0;
  return e;
}

}  // namespace

Body::Body(const DofLayout& layout) : layout_(layout) {
  if (layout.empty()) throw std::invalid_argument("Body: empty dof layout");
}

int Body::add_node(const Eigen::Vector3d& position) {
  nodes_.push_back(position);
  return num_nodes() - 1;
}

int Body::dof(int node, DofKind kind) const {
  for (int k = 0; k < dofs_per_node(); ++k)
    if (layout_[k] == kind) return dof(node, k);
  return -1;
}

int Body::add_element(std::shared_ptr<const Element> element, std::vector<int> nodes,
                      const Eigen::Matrix3d& R, const Eigen::Vector3d& origin) {
  if (!element) throw std::invalid_argument("Body::add_element: no element");
  if (element->node_layout() != layout_)
    throw std::invalid_argument("Body::add_element: the element's dof layout differs from the body's");
  if (static_cast<int>(nodes.size()) != element->num_nodes())
    throw std::invalid_argument("Body::add_element: expected " + std::to_string(element->num_nodes()) +
                                " nodes");
  if (!(R.transpose() * R).isIdentity(1e-12) || R.determinant() < 0.0)
    throw std::invalid_argument("Body::add_element: R is not a rotation");
  const Eigen::Matrix3Xd local = element->node_positions();
  double scale = 1.0;
  for (int i = 0; i < local.cols(); ++i) scale = std::max(scale, local.col(i).norm());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i] < 0 || nodes[i] >= num_nodes())
      throw std::invalid_argument("Body::add_element: no such node");
    if ((R * local.col(static_cast<int>(i)) + origin - nodes_[nodes[i]]).norm() > 1e-9 * scale)
      throw std::invalid_argument("Body::add_element: element node " + std::to_string(i) +
                                  " is not at body node " + std::to_string(nodes[i]));
  }
  // Per node: u^e = E blockdiag(R^T, R^T) E^T u_b; the layout must be closed under R.
  const Eigen::MatrixXd e = selector(layout_);
  Eigen::Matrix<double, 6, 6> rot = Eigen::Matrix<double, 6, 6>::Zero();
  rot.topLeftCorner<3, 3>() = R.transpose();
  rot.bottomRightCorner<3, 3>() = R.transpose();
  const Eigen::MatrixXd leak = (Eigen::MatrixXd::Identity(6, 6) - e.transpose() * e) * rot * e.transpose();
  if (leak.norm() > 1e-12)
    throw std::invalid_argument(
        "Body::add_element: R mixes dofs the layout does not have (planar bodies rotate "
        "elements about z only)");
  const Eigen::MatrixXd node_t = e * rot * e.transpose();
  const int ndpn = dofs_per_node(), ndof = element->num_dofs();
  ElementPlacement placed{
      std::move(element), std::move(nodes), R, origin, Eigen::MatrixXd::Zero(ndof, ndof), {}};
  for (std::size_t i = 0; i < placed.nodes.size(); ++i) {
    const int at = static_cast<int>(i) * ndpn;
    placed.T.block(at, at, ndpn, ndpn) = node_t;
    for (int k = 0; k < ndpn; ++k) placed.dofs.push_back(dof(placed.nodes[i], k));
  }
  elements_.push_back(std::move(placed));
  return num_elements() - 1;
}

void Body::add_point_mass(int node, double mass, const Eigen::Matrix3d& inertia) {
  if (imported_) throw std::invalid_argument("Body::add_point_mass: the body's mass matrix is imported");
  if (node < 0 || node >= num_nodes()) throw std::invalid_argument("Body::add_point_mass: no such node");
  if (!(mass >= 0.0)) throw std::invalid_argument("Body::add_point_mass: negative mass");
  point_masses_.push_back({node, mass, inertia});
}

Eigen::MatrixXd Body::scatter(const Eigen::MatrixXd& element_matrix, int e) const {
  const ElementPlacement& placed = elements_[e];
  const Eigen::MatrixXd body_frame = placed.T.transpose() * element_matrix * placed.T;
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(num_dofs(), num_dofs());
  for (std::size_t i = 0; i < placed.dofs.size(); ++i)
    for (std::size_t j = 0; j < placed.dofs.size(); ++j)
      full(placed.dofs[i], placed.dofs[j]) += body_frame(static_cast<int>(i), static_cast<int>(j));
  return full;
}

void Body::set_imported_matrices(Eigen::SparseMatrix<double> stiffness, Eigen::SparseMatrix<double> mass) {
  if (stiffness.rows() != num_dofs() || stiffness.cols() != num_dofs() || mass.rows() != num_dofs() ||
      mass.cols() != num_dofs())
    throw std::invalid_argument("Body::set_imported_matrices: the matrices are not num_dofs x num_dofs");
  if (!point_masses_.empty())
    throw std::invalid_argument("Body::set_imported_matrices: the body has point masses");
  imported_ = Imported{std::move(stiffness), std::move(mass)};
}

Eigen::MatrixXd Body::mass() const {
  if (imported_) return Eigen::MatrixXd(imported_->mass);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(num_dofs(), num_dofs());
  for (int e = 0; e < num_elements(); ++e) m += scatter(elements_[e].element->mass(), e);
  for (const PointMass& p : point_masses_) {
    const Eigen::MatrixXd t = node_translation(p.node), r = node_rotation(p.node);
    m += p.mass * t.transpose() * t + r.transpose() * p.inertia * r;
  }
  return m;
}

Eigen::MatrixXd Body::stiffness() const {
  if (imported_) return Eigen::MatrixXd(imported_->stiffness);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(num_dofs(), num_dofs());
  for (int e = 0; e < num_elements(); ++e) k += scatter(elements_[e].element->stiffness(), e);
  return k;
}

Eigen::MatrixXd Body::geometric_stiffness(const std::function<Prestress(int element)>& prestress) const {
  if (imported_)
    throw std::invalid_argument(
        "the body's stiffness is imported from a solver's matrices, which carry no element stresses for a "
        "geometric stiffness");
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(num_dofs(), num_dofs());
  for (int e = 0; e < num_elements(); ++e)
    k += scatter(elements_[e].element->geometric_stiffness(prestress(e)), e);
  return k;
}

MassPointGroup Body::element_mass_points(int e) const {
  const ElementPlacement& placed = elements_.at(e);
  MassPointGroup group{placed.dofs, placed.element->mass_points()};
  for (MassPoint& p : group.points) {
    p.r = placed.origin + placed.R * p.r;
    p.N = placed.R * p.N * placed.T;
    p.Nrot = placed.R * p.Nrot * placed.T;
    p.J = placed.R * p.J * placed.R.transpose();
  }
  return group;
}

std::vector<MassPointGroup> Body::mass_point_groups() const {
  std::vector<MassPointGroup> groups;
  for (int e = 0; e < num_elements(); ++e) groups.push_back(element_mass_points(e));
  for (const PointMass& pm : point_masses_) {
    MassPointGroup group;
    for (int k = 0; k < dofs_per_node(); ++k) group.dofs.push_back(dof(pm.node, k));
    MassPoint p;
    p.mass = pm.mass;
    p.r = nodes_[pm.node];
    p.J = pm.inertia;
    p.N = node_translation(pm.node)(Eigen::all, group.dofs);
    p.Nrot = node_rotation(pm.node)(Eigen::all, group.dofs);
    group.points.push_back(std::move(p));
    groups.push_back(std::move(group));
  }
  return groups;
}

Eigen::MatrixXd Body::node_translation(int node) const {
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(3, num_dofs());
  for (int k = 0; k < dofs_per_node(); ++k)
    if (kind_index(layout_[k]) < 3) t(kind_index(layout_[k]), dof(node, k)) = 1.0;
  return t;
}

Eigen::MatrixXd Body::node_rotation(int node) const {
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3, num_dofs());
  for (int k = 0; k < dofs_per_node(); ++k)
    if (kind_index(layout_[k]) >= 3) r(kind_index(layout_[k]) - 3, dof(node, k)) = 1.0;
  return r;
}

}  // namespace kanegen::fem
