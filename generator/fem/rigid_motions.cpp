// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/rigid_motions.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <vector>

namespace kanegen::fem {

namespace {

/// Singular values below this fraction of 1 (the bases are orthonormal) are
/// round-off: a held set would need an extent 1e-9 of its body's to come near.
constexpr double kRankTolerance = 1e-9;

/// The connected parts: for each body node, the smallest node of its part.
std::vector<int> part_of_nodes(const Body& body) {
  std::vector<int> root(static_cast<size_t>(body.num_nodes()));
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&](int n) {
    while (root[n] != n) n = root[n] = root[root[n]];
    return n;
  };
  for (int e = 0; e < body.num_elements(); ++e) {
    const std::vector<int>& nodes = body.element(e).nodes;
    for (int node : nodes) {
      const int a = find(nodes.front()), b = find(node);
      root[std::max(a, b)] = std::min(a, b);
    }
  }
  for (int n = 0; n < body.num_nodes(); ++n) root[n] = find(n);
  return root;
}

/// "(x, y, z)" with round-off shown as 0.
std::string vector_text(const Eigen::Vector3d& v) {
  const Eigen::Vector3d shown = (v.array().abs() > 1e-9 * v.norm()).select(v, 0.0) + Eigen::Vector3d::Zero();
  char text[96];
  std::snprintf(text, sizeof text, "(%.3g, %.3g, %.3g)", shown.x() + 0.0, shown.y() + 0.0, shown.z() + 0.0);
  return text;
}

/// The motions of one part, 6 columns (t_x, t_y, t_z, then theta about c
/// scaled by the part's size, so that every column is O(1) in any units).
Eigen::MatrixXd part_motions(const Body& body, const std::vector<int>& nodes, Eigen::Vector3d* c,
                             double* size) {
  *c = Eigen::Vector3d::Zero();
  for (int n : nodes) *c += body.node_position(n);
  *c /= static_cast<double>(nodes.size());
  *size = 0.0;
  for (int n : nodes) *size = std::max(*size, (body.node_position(n) - *c).norm());
  if (*size == 0.0) *size = 1.0;
  Eigen::MatrixXd motions = Eigen::MatrixXd::Zero(body.num_dofs(), 6);
  for (int n : nodes) {
    const Eigen::MatrixXd t = body.node_translation(n), r = body.node_rotation(n);
    const Eigen::Vector3d arm = (body.node_position(n) - *c) / *size;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k);
      motions.col(k) += t.transpose() * axis;
      motions.col(3 + k) += t.transpose() * axis.cross(arm) + r.transpose() * axis / *size;
    }
  }
  return motions;
}

}  // namespace

std::string unheld_rigid_motion(const Body& body, const Constraint& held) {
  const std::vector<int> part = part_of_nodes(body);
  for (int first = 0; first < body.num_nodes(); ++first) {
    if (part[first] != first) continue;
    std::vector<int> nodes;
    for (int n = first; n < body.num_nodes(); ++n)
      if (part[n] == first) nodes.push_back(n);
    Eigen::Vector3d c;
    double size = 0.0;
    const Eigen::MatrixXd motions = part_motions(body, nodes, &c, &size);
    // An orthonormal basis of what the part can do (a plane body: 3 motions).
    const Eigen::JacobiSVD<Eigen::MatrixXd> all(motions, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& s = all.singularValues();
    int rank = 0;
    while (rank < s.size() && s[rank] > kRankTolerance * s[0]) ++rank;
    const Eigen::MatrixXd basis = all.matrixU().leftCols(rank);
    // Its rows on the held dofs: a singular value near 0 is a motion they do not see.
    const Eigen::MatrixXd on_held = basis(held.fixed(), Eigen::all);
    Eigen::VectorXd v = Eigen::VectorXd::Unit(rank, 0);  // nothing held: any motion is free
    if (on_held.rows() > 0) {
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(on_held, Eigen::ComputeFullV);
      const Eigen::VectorXd& h = svd.singularValues();
      int seen = 0;
      while (seen < h.size() && h[seen] > kRankTolerance) ++seen;
      if (seen == rank) continue;
      v = svd.matrixV().col(rank - 1);
    }
    // The free motion in the columns' parameters: t, and theta / size.
    Eigen::VectorXd p = all.matrixV().leftCols(rank) * s.head(rank).cwiseInverse().asDiagonal() * v;
    const bool translation = p.tail<3>().norm() < 1e-6 * p.head<3>().norm();
    // Named with its largest component positive (-p is the same motion).
    Eigen::Index largest = 0;
    const Eigen::Vector3d named = translation ? p.head<3>() : p.tail<3>();
    named.cwiseAbs().maxCoeff(&largest);
    if (named[largest] < 0) p = -p;
    const Eigen::Vector3d t = p.head<3>(), theta = p.tail<3>() / size;
    const std::string of_part = " of the part with node " + std::to_string(first);
    if (translation) return "a translation along " + vector_text(t.normalized()) + of_part;
    // The axis through c + theta x t / |theta|^2, where the motion is along the axis only.
    const Eigen::Vector3d through = c + theta.cross(t) / theta.squaredNorm();
    return "a rotation about the axis " + vector_text(theta.normalized()) + " through " +
           vector_text(through) + of_part;
  }
  return "";
}

}  // namespace kanegen::fem
