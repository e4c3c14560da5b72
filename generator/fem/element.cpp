// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/element.hpp"

namespace kanegen::fem {

const DofLayout& planar_layout() {
  static const DofLayout layout{DofKind::kUx, DofKind::kUy, DofKind::kRz};
  return layout;
}

const DofLayout& spatial_layout() {
  static const DofLayout layout{DofKind::kUx, DofKind::kUy, DofKind::kUz,
                                DofKind::kRx, DofKind::kRy, DofKind::kRz};
  return layout;
}

const DofLayout& plane_layout() {
  static const DofLayout layout{DofKind::kUx, DofKind::kUy};
  return layout;
}

const DofLayout& solid_layout() {
  static const DofLayout layout{DofKind::kUx, DofKind::kUy, DofKind::kUz};
  return layout;
}

Eigen::MatrixXd Element::mass() const {
  const int n = num_dofs();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (const MassPoint& p : mass_points()) {
    m.noalias() += p.mass * p.N.transpose() * p.N;
    m.noalias() += p.Nrot.transpose() * p.J * p.Nrot;
  }
  return 0.5 * (m + m.transpose());  // exactly symmetric
}

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

}  // namespace kanegen::fem
