// SPDX-License-Identifier: GPL-2.0-or-later
#include "numeric/loops.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "numeric/dual.hpp"

namespace kanegen::numeric {

LoopKinematics loop_kinematics(const Instance& m, const std::vector<double>& q,
                               const std::vector<double>& u) {
  using D1 = Dual<double>;
  using D2 = Dual<D1>;
  const int n = m.coordinates();
  LoopKinematics k;
  k.phi = loop_residuals(m, q.data());
  const int nc = static_cast<int>(k.phi.size());
  k.jacobian.assign(static_cast<std::size_t>(nc) * n, 0.0);
  // Column r of C: Phi along e_r.
  std::vector<D1> seeded(n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) seeded[c] = D1(q[c], c == r ? 1.0 : 0.0);
    const std::vector<D1> column = loop_residuals(m, seeded.data());
    for (int i = 0; i < nc; ++i) k.jacobian[i * n + r] = column[i].d;
  }
  // gamma = -u^T (d2 Phi/dq2) u, the second derivative along u.
  std::vector<D2> path(n);
  for (int c = 0; c < n; ++c) path[c] = D2(D1(q[c], u[c]), D1(u[c], 0.0));
  const std::vector<D2> along = loop_residuals(m, path.data());
  for (const D2& x : along) k.bias.push_back(-x.d.d);
  return k;
}

ConstrainedSolution solve_constrained(int n, const std::vector<double>& mass_matrix,
                                      const std::vector<double>& forcing, const LoopKinematics& loops,
                                      const std::vector<int>& prescribed,
                                      const std::vector<double>& prescribed_acceleration) {
  ConstrainedSolution out;
  const int nc = static_cast<int>(loops.phi.size());
  std::vector<double> udot(n, 0.0);
  std::vector<char> given(n, 0);
  for (std::size_t p = 0; p < prescribed.size(); ++p) {
    udot[prescribed[p]] = prescribed_acceleration[p];
    given[prescribed[p]] = 1;
  }
  std::vector<int> free;
  for (int r = 0; r < n; ++r)
    if (!given[r]) free.push_back(r);
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd mff(nf, nf), cf(nc, nf);
  Eigen::VectorXd rhs(nf), g(nc);
  for (int a = 0; a < nf; ++a) {
    rhs[a] = forcing[free[a]];
    for (int p : prescribed) rhs[a] -= mass_matrix[free[a] * n + p] * udot[p];
    for (int c = 0; c < nf; ++c) mff(a, c) = mass_matrix[free[a] * n + free[c]];
  }
  for (int i = 0; i < nc; ++i) {
    g[i] = loops.bias[i];
    for (int p : prescribed) g[i] -= loops.jacobian[i * n + p] * udot[p];
    for (int a = 0; a < nf; ++a) cf(i, a) = loops.jacobian[i * n + free[a]];
  }
  // The range-space method, the textbook solution of the saddle-point system
  // (an independent route: a symmetric eigen-free Cholesky of M and of S).
  const Eigen::LLT<Eigen::MatrixXd> m_factor(mff);
  if (m_factor.info() != Eigen::Success) return out;
  const Eigen::MatrixXd minv_ct = m_factor.solve(cf.transpose());
  const Eigen::VectorXd minv_f = m_factor.solve(rhs);
  const Eigen::MatrixXd s = cf * minv_ct;
  const Eigen::LLT<Eigen::MatrixXd> s_factor(s);
  if (s_factor.info() != Eigen::Success) return out;
  const Eigen::VectorXd lambda = s_factor.solve(g - cf * minv_f);
  const Eigen::VectorXd x = minv_f + minv_ct * lambda;
  for (int a = 0; a < nf; ++a) udot[free[a]] = x[a];
  out.ok = true;
  out.udot = udot;
  out.lambda.assign(lambda.data(), lambda.data() + nc);
  return out;
}

bool project_onto_loops(const Instance& m, const std::vector<int>& held, std::vector<double>& q,
                        std::vector<double>& u) {
  const int n = m.coordinates();
  std::vector<int> free;
  for (int r = 0; r < n; ++r)
    if (std::find(held.begin(), held.end(), r) == held.end()) free.push_back(r);
  const auto free_columns = [&](const LoopKinematics& k) {
    const int nc = static_cast<int>(k.phi.size());
    Eigen::MatrixXd cf(nc, free.size());
    for (int i = 0; i < nc; ++i)
      for (std::size_t a = 0; a < free.size(); ++a) cf(i, a) = k.jacobian[i * n + free[a]];
    return cf;
  };
  std::vector<double> x = q, v = u;
  for (int step = 0;; ++step) {
    const LoopKinematics k = loop_kinematics(m, x, v);
    const Eigen::Map<const Eigen::VectorXd> phi(k.phi.data(), static_cast<Eigen::Index>(k.phi.size()));
    if (phi.lpNorm<Eigen::Infinity>() <= 1e-12) break;
    if (step == 50 || !std::isfinite(phi.lpNorm<Eigen::Infinity>())) return false;
    Eigen::VectorXd dq = free_columns(k).completeOrthogonalDecomposition().solve(phi);
    if (dq.norm() > 0.5) dq *= 0.5 / dq.norm();  // far from closing: damped, so Newton does not jump branches
    for (std::size_t a = 0; a < free.size(); ++a) x[free[a]] -= dq[a];
  }
  const LoopKinematics k = loop_kinematics(m, x, v);
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(k.phi.size()));
  for (std::size_t i = 0; i < k.phi.size(); ++i)
    for (int c = 0; c < n; ++c) velocity[i] += k.jacobian[i * n + c] * v[c];
  const Eigen::VectorXd du = free_columns(k).completeOrthogonalDecomposition().solve(velocity);
  for (std::size_t a = 0; a < free.size(); ++a) v[free[a]] -= du[a];
  q = x;
  u = v;
  return true;
}

}  // namespace kanegen::numeric
