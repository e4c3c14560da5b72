// SPDX-License-Identifier: GPL-2.0-or-later
// A flexible body: nodes in the link frame, elements placed by a constant
// rotation R^e, point masses on nodes, and the assembled matrices.
//
// Body dofs are nodal components in the LINK frame, numbered node by node:
// dof(node, k) = node * dofs_per_node + k, k in the body's layout (planar:
// u_x, u_y, theta_z; spatial: u_x, u_y, u_z, theta_x, theta_y, theta_z).
// An element's own dofs u^e (element-frame components) are u^e = T_e u_b,
// u_b the body dofs of its nodes in element_dofs(e) order, T_e =
// blockdiag(R^e^T, R^e^T) restricted to the layout. So a point of element e
// is at r + R^e N^e T_e u_b in the link frame (the seed's R^e N^e u^e).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "fem/element.hpp"

namespace kanegen::fem {

struct ElementPlacement {
  std::shared_ptr<const Element> element;
  std::vector<int> nodes;  ///< body node of each element node
  Eigen::Matrix3d R;       ///< R^e: its columns are the element axes in the link frame
  Eigen::Vector3d origin;  ///< the element frame's origin in the link frame
  Eigen::MatrixXd T;       ///< ndof_e x ndof_e: u^e = T u_b
  std::vector<int> dofs;   ///< ndof_e body dofs, node by node
};

/// Mass points in the link frame whose N and Nrot columns are the body dofs `dofs`.
struct MassPointGroup {
  std::vector<int> dofs;
  std::vector<MassPoint> points;
};

class Body {
 public:
  explicit Body(const DofLayout& layout);

  /// Returns the node's index. position: undeformed, link frame.
  int add_node(const Eigen::Vector3d& position);
  /// Places an element; its node positions R p + origin must coincide with
  /// the body nodes given, and R must keep the layout (a planar layout allows
  /// only rotations about z). Returns the element's index.
  int add_element(std::shared_ptr<const Element> element, std::vector<int> nodes, const Eigen::Matrix3d& R,
                  const Eigen::Vector3d& origin);
  /// A rigid body on a node (tip mass): mass in kg, inertia about the node in the link frame (kg m^2).
  void add_point_mass(int node, double mass, const Eigen::Matrix3d& inertia = Eigen::Matrix3d::Zero());

  const DofLayout& layout() const { return layout_; }
  int dofs_per_node() const { return static_cast<int>(layout_.size()); }
  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  int num_dofs() const { return num_nodes() * dofs_per_node(); }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  int dof(int node, int k) const { return node * dofs_per_node() + k; }
  /// The dof of this kind at the node, or -1 if the layout has none.
  int dof(int node, DofKind kind) const;
  const Eigen::Vector3d& node_position(int node) const { return nodes_.at(node); }
  const ElementPlacement& element(int e) const { return elements_.at(e); }

  /// M: num_dofs x num_dofs, consistent mass including point masses; the
  /// imported matrix instead, if the body has one.
  Eigen::MatrixXd mass() const;
  /// K_e: num_dofs x num_dofs; the imported matrix instead, if the body has one.
  Eigen::MatrixXd stiffness() const;

  /// K and M from a solver's files (fem/ccx_matrices.hpp), num_dofs x num_dofs
  /// in body dofs, both triangles: they replace the elements' K and M in
  /// stiffness(), mass(), sparse_stiffness() and sparse_mass(). The elements
  /// stay (node positions, mass points of the inertia invariants). No point
  /// masses may be added before or after.
  void set_imported_matrices(Eigen::SparseMatrix<double> stiffness, Eigen::SparseMatrix<double> mass);
  bool has_imported_matrices() const { return imported_.has_value(); }
  const Eigen::SparseMatrix<double>& imported_stiffness() const { return imported_->stiffness; }
  const Eigen::SparseMatrix<double>& imported_mass() const { return imported_->mass; }
  /// K_G: num_dofs x num_dofs for the prestress of each element; refused
  /// (std::invalid_argument) for a body with imported matrices.
  Eigen::MatrixXd geometric_stiffness(const std::function<Prestress(int element)>& prestress) const;

  /// Element e's mass points, transformed to the link frame and to body dofs.
  MassPointGroup element_mass_points(int e) const;
  /// Every mass point of the body: one group per element, then one per point mass.
  std::vector<MassPointGroup> mass_point_groups() const;

  /// 3 x num_dofs: the node's displacement in the link frame is node_translation(node) u.
  Eigen::MatrixXd node_translation(int node) const;
  /// 3 x num_dofs: the node's small rotation in the link frame (planar: only the z row).
  Eigen::MatrixXd node_rotation(int node) const;

 private:
  Eigen::MatrixXd scatter(const Eigen::MatrixXd& element_matrix, int e) const;

  DofLayout layout_;
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<ElementPlacement> elements_;
  struct PointMass {
    int node;
    double mass;
    Eigen::Matrix3d inertia;
  };
  std::vector<PointMass> point_masses_;
  struct Imported {
    Eigen::SparseMatrix<double> stiffness, mass;
  };
  std::optional<Imported> imported_;
};

}  // namespace kanegen::fem
