// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/invariants.hpp"

#include <stdexcept>

namespace kanegen::fem {

InertiaInvariants InertiaInvariants::zero(int n) {
  InertiaInvariants inv;
  inv.n = n;
  inv.S = Eigen::MatrixXd::Zero(3, n);
  inv.S_r = Eigen::MatrixXd::Zero(9, n);
  for (auto& m : inv.S_nn) m = Eigen::MatrixXd::Zero(n, n);
  inv.J_Nrot = Eigen::MatrixXd::Zero(3, n);
  inv.Nrot_J_Nrot = Eigen::MatrixXd::Zero(n, n);
  return inv;
}

Eigen::MatrixXd InertiaInvariants::skew_r_N() const {
  // Row a of skew(r) N is sum_b eps_{a c b} r_c N_b.
  Eigen::MatrixXd out(3, n);
  out.row(0) = S_r.row(3 * 1 + 2) - S_r.row(3 * 2 + 1);  // r_y N_z - r_z N_y
  out.row(1) = S_r.row(3 * 2 + 0) - S_r.row(3 * 0 + 2);  // r_z N_x - r_x N_z
  out.row(2) = S_r.row(3 * 0 + 1) - S_r.row(3 * 1 + 0);  // r_x N_y - r_y N_x
  return out;
}

Eigen::MatrixXd InertiaInvariants::NtN() const { return S_nn[0] + S_nn[4] + S_nn[8]; }

Eigen::MatrixXd InertiaInvariants::coriolis(int c) const {
  // N^T skew(e_c) N = sum_ab skew(e_c)_ab N_a^T N_b, skew(e_c) having +1 at (c+2, c+1), -1 at (c+1, c+2).
  switch (c) {
    case 0:
      return S_nn[3 * 2 + 1] - S_nn[3 * 1 + 2];  // (z, y) - (y, z)
    case 1:
      return S_nn[3 * 0 + 2] - S_nn[3 * 2 + 0];  // (x, z) - (z, x)
    case 2:
      return S_nn[3 * 1 + 0] - S_nn[3 * 0 + 1];  // (y, x) - (x, y)
    default:
      throw std::invalid_argument("InertiaInvariants::coriolis: axis must be 0, 1 or 2");
  }
}

Eigen::MatrixXd InertiaInvariants::elastic_mass() const { return NtN() + Nrot_J_Nrot; }

InertiaInvariants invariants(const MassPointGroup& group) {
  const int n = static_cast<int>(group.dofs.size());
  InertiaInvariants inv = InertiaInvariants::zero(n);
  for (const MassPoint& p : group.points) {
    if (p.N.rows() != 3 || p.N.cols() != n || p.Nrot.rows() != 3 || p.Nrot.cols() != n)
      throw std::invalid_argument("invariants: a mass point's N or Nrot is not 3 x n");
    const double m = p.mass;
    inv.mass += m;
    inv.first_moment += m * p.r;
    inv.second_moment += m * p.r * p.r.transpose();
    inv.S += m * p.N;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) inv.S_r.row(3 * a + b) += (m * p.r[a]) * p.N.row(b);
      for (int b = a; b < 3; ++b) inv.S_nn[3 * a + b].noalias() += m * p.N.row(a).transpose() * p.N.row(b);
    }
    inv.J += p.J;
    inv.J_Nrot += p.J * p.Nrot;
    inv.Nrot_J_Nrot.noalias() += p.Nrot.transpose() * p.J * p.Nrot;
  }
  // Exact symmetry (S_nn[3b+a] = S_nn[3a+b]^T), so that nothing downstream sees rounding asymmetry.
  for (int a = 0; a < 3; ++a) {
    inv.S_nn[4 * a] = 0.5 * (inv.S_nn[4 * a] + inv.S_nn[4 * a].transpose()).eval();
    for (int b = a + 1; b < 3; ++b) inv.S_nn[3 * b + a] = inv.S_nn[3 * a + b].transpose();
  }
  inv.Nrot_J_Nrot = 0.5 * (inv.Nrot_J_Nrot + inv.Nrot_J_Nrot.transpose()).eval();
  return inv;
}

void add_scattered(InertiaInvariants& into, const InertiaInvariants& part, const std::vector<int>& dofs) {
  if (static_cast<int>(dofs.size()) != part.n)
    throw std::invalid_argument("add_scattered: dofs do not match");
  into.mass += part.mass;
  into.first_moment += part.first_moment;
  into.second_moment += part.second_moment;
  into.J += part.J;
  into.S(Eigen::all, dofs) += part.S;
  into.S_r(Eigen::all, dofs) += part.S_r;
  into.J_Nrot(Eigen::all, dofs) += part.J_Nrot;
  into.Nrot_J_Nrot(dofs, dofs) += part.Nrot_J_Nrot;
  for (int k = 0; k < 9; ++k) into.S_nn[k](dofs, dofs) += part.S_nn[k];
}

InertiaInvariants element_invariants(const Body& body, int e) {
  return invariants(body.element_mass_points(e));
}

InertiaInvariants body_invariants(const Body& body) {
  InertiaInvariants inv = InertiaInvariants::zero(body.num_dofs());
  for (const MassPointGroup& group : body.mass_point_groups())
    add_scattered(inv, invariants(group), group.dofs);
  return inv;
}

InertiaInvariants transform(const InertiaInvariants& inv, const Eigen::MatrixXd& B) {
  if (B.rows() != inv.n) throw std::invalid_argument("transform: B must have n rows");
  InertiaInvariants out = inv;
  out.n = static_cast<int>(B.cols());
  out.S = inv.S * B;
  out.S_r = inv.S_r * B;
  for (int k = 0; k < 9; ++k) out.S_nn[k] = B.transpose() * inv.S_nn[k] * B;
  out.J_Nrot = inv.J_Nrot * B;
  out.Nrot_J_Nrot = B.transpose() * inv.Nrot_J_Nrot * B;
  return out;
}

}  // namespace kanegen::fem
