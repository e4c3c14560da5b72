// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/craig_bampton.hpp"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <set>
#include <stdexcept>

#include "fem/modal.hpp"
#include "fem/sparse_assembly.hpp"

namespace kanegen::fem {

namespace {

/// num_dofs x r: the rigid motions of one interface about its centroid
/// (translations, then small rotations; the plane has u_x, u_y, theta_z).
Eigen::MatrixXd rigid_motions(const Body& body, const std::vector<int>& nodes) {
  const int d = body.dofs_per_node();
  const int r = d == 2 ? 3 : 6;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int n : nodes) c += body.node_position(n);
  c /= static_cast<double>(nodes.size());
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(body.num_dofs(), r);
  for (int n : nodes) {
    const Eigen::Vector3d x = body.node_position(n) - c;
    for (int a = 0; a < d; ++a) t(body.dof(n, a), a) = 1.0;
    // theta x x, one rotation axis at a time.
    const int first_axis = d == 2 ? 2 : 0;
    for (int axis = first_axis; axis < 3; ++axis) {
      const Eigen::Vector3d motion = Eigen::Vector3d::Unit(axis).cross(x);
      for (int a = 0; a < d; ++a) t(body.dof(n, a), d + axis - first_axis) = motion(a);
    }
  }
  return t;
}

/// Constraint modes, dense: u_B given, u_I = -K_II^-1 K_IB u_B.
std::vector<Eigen::MatrixXd> static_modes(const Constraint& fixed_interface, const Eigen::MatrixXd& K,
                                          const std::vector<Eigen::MatrixXd>& u_Bs) {
  const Eigen::MatrixXd P_I = fixed_interface.selection();
  const Eigen::LDLT<Eigen::MatrixXd> K_II(P_I.transpose() * K * P_I);
  if (K_II.info() != Eigen::Success)
    throw std::invalid_argument("craig_bampton: singular interior stiffness");
  std::vector<Eigen::MatrixXd> psi;
  for (const Eigen::MatrixXd& u_B : u_Bs) psi.push_back(u_B - P_I * K_II.solve(P_I.transpose() * K * u_B));
  return psi;
}

/// The same by sparse solves: K_II factored once (sparse LDL^T), one solve per rigid motion.
std::vector<Eigen::MatrixXd> static_modes(const Constraint& fixed_interface,
                                          const Eigen::SparseMatrix<double>& K,
                                          const std::vector<Eigen::MatrixXd>& u_Bs) {
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> K_II(reduce_sparse(fixed_interface, K));
  if (K_II.info() != Eigen::Success || (K_II.vectorD().array() <= 0.0).any())
    throw std::invalid_argument("craig_bampton: singular interior stiffness");
  std::vector<Eigen::MatrixXd> psi;
  for (const Eigen::MatrixXd& u_B : u_Bs) {
    const Eigen::MatrixXd K_IB_u_B = (K * u_B)(fixed_interface.free(), Eigen::all);
    psi.push_back(u_B - fixed_interface.expand(K_II.solve(K_IB_u_B)));
  }
  return psi;
}

ModalBasis interior_modes(const Body& body, const Constraint& fixed_interface, const Eigen::MatrixXd& K,
                          int k) {
  return modal_analysis(fixed_interface.reduce(body.mass()), fixed_interface.reduce(K), k);
}

ModalBasis interior_modes(const Body& body, const Constraint& fixed_interface,
                          const Eigen::SparseMatrix<double>& K, int k) {
  return sparse_modal_analysis(reduce_sparse(fixed_interface, sparse_mass(body)),
                               reduce_sparse(fixed_interface, K), k);
}

/// [Psi, Phi] of unit modal mass each, with K dense or sparse.
template <typename Matrix, typename Mass>
CraigBamptonBasis assemble(const Body& body, const Constraint& fixed_interface,
                           const std::vector<std::vector<int>>& interfaces, int k, const Matrix& K,
                           const Mass& mass) {
  std::vector<Eigen::MatrixXd> u_Bs;
  int columns = 0;
  for (const std::vector<int>& nodes : interfaces) {
    u_Bs.push_back(rigid_motions(body, nodes));
    columns += static_cast<int>(u_Bs.back().cols());
  }
  const std::vector<Eigen::MatrixXd> psi = static_modes(fixed_interface, K, u_Bs);
  const ModalBasis modes = interior_modes(body, fixed_interface, K, k);
  CraigBamptonBasis out;
  out.constraint_modes = columns;
  out.omega = modes.omega;
  out.basis.resize(body.num_dofs(), columns + k);
  // Each constraint mode scaled to unit modal mass, as the fixed-interface modes are: a small bore's
  // unit rotation moves little mass, and unscaled its coordinate's inertia would be 1e-6 of the others'.
  const auto M = mass();
  int at = 0;
  for (const Eigen::MatrixXd& p : psi) {
    for (Eigen::Index j = 0; j < p.cols(); ++j)
      out.basis.col(at + j) = p.col(j) / std::sqrt(p.col(j).dot(M * p.col(j)));
    at += static_cast<int>(p.cols());
  }
  out.basis.rightCols(k) = fixed_interface.expand(modes.shapes);
  return out;
}

}  // namespace

CraigBamptonBasis craig_bampton(const Body& body, const Constraint& held,
                                const std::vector<std::vector<int>>& interfaces, int k, ModalPath path) {
  const int n = body.num_dofs();
  std::vector<int> boundary = held.fixed();
  std::set<int> held_set(held.fixed().begin(), held.fixed().end());
  for (const std::vector<int>& nodes : interfaces) {
    if (nodes.size() < 2) throw std::invalid_argument("an interface needs two or more nodes");
    for (int node : nodes)
      for (int a = 0; a < body.dofs_per_node(); ++a) {
        if (held_set.count(body.dof(node, a))) throw std::invalid_argument("an interface shares held dofs");
        boundary.push_back(body.dof(node, a));
      }
  }
  const Constraint fixed_interface(n, boundary);  // every interface dof and the held ones
  if (k < 1 || k > fixed_interface.num_free())
    throw std::invalid_argument("craig_bampton: bad fixed-interface mode count");
  if (use_sparse_path(fixed_interface.num_free(), path) &&
      (path == ModalPath::kSparse || 2 * k <= fixed_interface.num_free()))
    return assemble(body, fixed_interface, interfaces, k, sparse_stiffness(body),
                    [&] { return sparse_mass(body); });
  return assemble(body, fixed_interface, interfaces, k, body.stiffness(), [&] { return body.mass(); });
}

}  // namespace kanegen::fem
