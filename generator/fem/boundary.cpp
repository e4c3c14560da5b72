// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/boundary.hpp"

#include <algorithm>
#include <stdexcept>

namespace kanegen::fem {

Constraint::Constraint(int num_dofs, std::vector<int> fixed) : n_(num_dofs), reduced_(num_dofs, -1) {
  std::vector<bool> is_fixed(num_dofs, false);
  for (int d : fixed) {
    if (d < 0 || d >= num_dofs) throw std::invalid_argument("Constraint: dof out of range");
    is_fixed[d] = true;
  }
  for (int d = 0; d < num_dofs; ++d) {
    if (is_fixed[d]) {
      fixed_.push_back(d);
    } else {
      reduced_[d] = static_cast<int>(free_.size());
      free_.push_back(d);
    }
  }
}

Eigen::MatrixXd Constraint::selection() const {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n_, num_free());
  for (int i = 0; i < num_free(); ++i) p(free_[i], i) = 1.0;
  return p;
}

Eigen::MatrixXd Constraint::reduce(const Eigen::MatrixXd& a) const {
  if (a.rows() != n_ || a.cols() != n_) throw std::invalid_argument("Constraint::reduce: wrong size");
  return a(free_, free_);
}

Eigen::MatrixXd Constraint::expand(const Eigen::MatrixXd& x) const {
  if (x.rows() != num_free()) throw std::invalid_argument("Constraint::expand: wrong size");
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(n_, x.cols());
  full(free_, Eigen::all) = x;
  return full;
}

Constraint support_constraint(const Body& body, Support support, int first_node, int last_node) {
  if (last_node < 0) last_node = body.num_nodes() - 1;
  if (first_node < 0 || first_node >= body.num_nodes() || last_node >= body.num_nodes())
    throw std::invalid_argument("support_constraint: no such node");
  std::vector<int> fixed;
  auto fix = [&](int node, DofKind kind) {
    const int d = body.dof(node, kind);
    if (d >= 0) fixed.push_back(d);
  };
  switch (support) {
    case Support::kClamped:
      for (int k = 0; k < body.dofs_per_node(); ++k) fixed.push_back(body.dof(first_node, k));
      break;
    case Support::kPinnedPinned:
      // Kinds a planar layout lacks (u_z, theta_x) are skipped by fix().
      for (DofKind kind : {DofKind::kUx, DofKind::kUy, DofKind::kUz, DofKind::kRx}) fix(first_node, kind);
      for (DofKind kind : {DofKind::kUy, DofKind::kUz}) fix(last_node, kind);
      break;
    case Support::kFree:
      break;
  }
  return Constraint(body.num_dofs(), std::move(fixed));
}

}  // namespace kanegen::fem
