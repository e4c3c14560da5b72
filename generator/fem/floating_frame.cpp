// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/floating_frame.hpp"

#include <stdexcept>

namespace kanegen::fem {

namespace {

void check(const InertiaInvariants& inv, const Eigen::VectorXd& q) {
  if (q.size() != inv.n) throw std::invalid_argument("floating frame: q must have n entries");
}

/// int rho skew(N q) N: 3 x n; row a is sum_bc eps_abc q^T S_nn[3b+c].
Eigen::MatrixXd skew_Nq_N(const InertiaInvariants& inv, const Eigen::VectorXd& q) {
  Eigen::MatrixXd out(3, inv.n);
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    out.row(a) = q.transpose() * (inv.S_nn[3 * b + c] - inv.S_nn[3 * c + b]);
  }
  return out;
}

Eigen::Matrix3d inertia_tensor(const Eigen::Matrix3d& second_moment) {
  return second_moment.trace() * Eigen::Matrix3d::Identity() - second_moment;
}

}  // namespace

Eigen::Matrix3d deformed_second_moment(const InertiaInvariants& inv, const Eigen::VectorXd& q) {
  check(inv, q);
  Eigen::Matrix3d c;  // int rho r_a (N q)_b
  Eigen::Matrix3d d;  // int rho (N q)_a (N q)_b
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      c(a, b) = inv.S_r.row(3 * a + b).dot(q);
      // Symmetric; q.S_nn[3b+a] q rounds differently from its twin q.S_nn[3a+b] q.
      d(a, b) = b < a ? d(b, a) : q.dot(inv.S_nn[3 * a + b] * q);
    }
  return inv.second_moment + (c + c.transpose()) + d;  // grouped so that the sum is symmetric too
}

Eigen::MatrixXd ffr_mass_matrix(const InertiaInvariants& inv, const Eigen::VectorXd& q) {
  check(inv, q);
  const int n = inv.n;
  const Eigen::Vector3d s_p = inv.first_moment + inv.S * q;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(6 + n, 6 + n);
  m.block<3, 3>(0, 0) = inv.mass * Eigen::Matrix3d::Identity();
  m.block<3, 3>(0, 3) = -skew(s_p);
  m.block(0, 6, 3, n) = inv.S;
  m.block<3, 3>(3, 3) = inertia_tensor(deformed_second_moment(inv, q)) + inv.J;
  m.block(3, 6, 3, n) = inv.skew_r_N() + skew_Nq_N(inv, q) + inv.J_Nrot;
  m.block(6, 6, n, n) = inv.elastic_mass();
  m.block<3, 3>(3, 0) = m.block<3, 3>(0, 3).transpose();
  m.block(6, 0, n, 6) = m.block(0, 6, 6, n).transpose();
  return m;
}

Eigen::VectorXd ffr_velocity_forces(const InertiaInvariants& inv, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& qdot, const Eigen::Vector3d& omega) {
  check(inv, q);
  check(inv, qdot);
  const int n = inv.n;
  const Eigen::Matrix3d W = skew(omega), W2 = W * W;
  const Eigen::Vector3d s_p = inv.first_moment + inv.S * q;
  Eigen::VectorXd f(6 + n);

  f.head<3>() = -(W2 * s_p + 2.0 * W * (inv.S * qdot));

  // int rho r_p x (omega x d), d = N qdot: omega int rho r_p.d - int rho d (r_p.omega).
  double rp_dot_d = 0.0;
  Eigen::Vector3d d_rp_omega = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a) {
    rp_dot_d += inv.S_r.row(4 * a).dot(qdot) + q.dot(inv.S_nn[4 * a] * qdot);
    for (int b = 0; b < 3; ++b)
      d_rp_omega[b] += omega[a] * (inv.S_r.row(3 * a + b).dot(qdot) + q.dot(inv.S_nn[3 * a + b] * qdot));
  }
  const Eigen::Matrix3d inertia = inertia_tensor(deformed_second_moment(inv, q)) + inv.J;
  f.segment<3>(3) = -(omega.cross(inertia * omega) + omega.cross(Eigen::Vector3d(inv.J_Nrot * qdot)) +
                      2.0 * (omega * rp_dot_d - d_rp_omega));

  // int rho N^T W^2 r_p = sum_ab (W^2)_ab (int rho N_a^T r_b + int rho N_a^T N_b q).
  Eigen::VectorXd centrifugal = Eigen::VectorXd::Zero(n);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      centrifugal += W2(a, b) * (inv.S_r.row(3 * b + a).transpose() + inv.S_nn[3 * a + b] * q);
  Eigen::VectorXd coriolis = Eigen::VectorXd::Zero(n);
  for (int c = 0; c < 3; ++c) coriolis += omega[c] * (inv.coriolis(c) * qdot);
  f.tail(n) = -(centrifugal + 2.0 * coriolis);
  return f;
}

Eigen::VectorXd ffr_gravity_forces(const InertiaInvariants& inv, const Eigen::VectorXd& q,
                                   const Eigen::Vector3d& g) {
  check(inv, q);
  Eigen::VectorXd f(6 + inv.n);
  f.head<3>() = inv.mass * g;
  f.segment<3>(3) = Eigen::Vector3d(inv.first_moment + inv.S * q).cross(g);
  f.tail(inv.n) = inv.S.transpose() * g;
  return f;
}

}  // namespace kanegen::fem
