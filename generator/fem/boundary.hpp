// SPDX-License-Identifier: GPL-2.0-or-later
// Boundary conditions in the link frame: which body dofs are held at zero,
// and the map between the full dofs u (num_dofs) and the free ones u_r:
// u = P u_r, P the num_dofs x num_free selection of the free dofs.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "fem/body.hpp"

namespace kanegen::fem {

/// Supports of a straight beam, between its first node (the joint) and its last node:
///  - kClamped: every dof of the first node fixed (a cantilever on the joint);
///  - kPinnedPinned: a rod between two pins, the link frame's x axis from pin to pin:
///    planar: u_x, u_y at the first node and u_y at the last;
///    spatial: u_x, u_y, u_z, theta_x at the first node (theta_x removes the spin
///    about the axis) and u_y, u_z at the last;
///  - kFree: nothing fixed (K is singular; rigid motions belong to the joints).
enum class Support { kClamped, kPinnedPinned, kFree };

class Constraint {
 public:
  /// Fixes the given dofs (any order, duplicates ignored) of a body with num_dofs dofs.
  Constraint(int num_dofs, std::vector<int> fixed);

  int num_dofs() const { return n_; }
  int num_free() const { return static_cast<int>(free_.size()); }
  const std::vector<int>& fixed() const { return fixed_; }  ///< ascending
  const std::vector<int>& free() const { return free_; }  ///< ascending: reduced dof i is full dof free()[i]
  /// Reduced index of a full dof, or -1 if it is fixed.
  int reduced_index(int full_dof) const { return reduced_.at(full_dof); }

  /// P: num_dofs x num_free.
  Eigen::MatrixXd selection() const;
  /// P^T A P: num_free x num_free.
  Eigen::MatrixXd reduce(const Eigen::MatrixXd& a) const;
  /// P x: num_dofs x cols, zeros on the fixed dofs.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& x) const;

 private:
  int n_;
  std::vector<int> fixed_, free_, reduced_;
};

/// The support's fixed dofs for body, with first and last node as above (last = -1: the body's last node).
Constraint support_constraint(const Body& body, Support support, int first_node = 0, int last_node = -1);

}  // namespace kanegen::fem
