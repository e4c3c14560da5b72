// SPDX-License-Identifier: MIT
#include "kanegen/runtime/state_jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cholesky.hpp"
#include "kanegen/runtime/loops.hpp"

namespace kanegen::runtime {

std::string missing_jacobians_message(const ModelInfo& info) {
  return std::string("model ") + info.name +
         " has no Jacobian kernels, which the implicit integrators need: regenerate it with "
         "'kanegen generate --jacobians' (kanegen simulate --integrator implicit|genalpha does it itself)";
}

std::vector<char> prescribed_coordinates(const Model& model) {
  const ModelInfo& info = model.info();
  std::vector<char> prescribed(static_cast<size_t>(std::max(info.nu, 0)), 0);
  if (info.coordinate_roles) {
    for (int i = 0; i < info.nu; ++i) prescribed[i] = info.coordinate_roles[i] == 2;
    return prescribed;
  }
  const int m = info.nu;
  std::vector<double> q(std::max(m, 1)), u(std::max(m, 1)), a(std::max(m, 1)), b(std::max(m, 1)),
      tau(std::max(info.ntau, 1), 0.0);
  model.initial_state(q.data(), u.data());
  const double t = 0.1;
  if (model.forward_dynamics(t, q.data(), u.data(), tau.data(), a.data()) != 0) return prescribed;
  // Every component moved, by different amounts, so that no cancellation hides a dependence.
  for (int i = 0; i < m; ++i) {
    q[i] += 1e-3 * (1.0 + std::abs(q[i])) * (1.0 + 0.37 * i);
    u[i] += 1e-2 * (1.0 + std::abs(u[i])) * (1.0 + 0.53 * i);
  }
  if (model.forward_dynamics(t, q.data(), u.data(), tau.data(), b.data()) != 0) return prescribed;
  for (int i = 0; i < m; ++i) prescribed[i] = a[i] == b[i];
  return prescribed;
}

StateJacobian::StateJacobian(const Model& model)
    : model_(model), m_(model.info().nu), nc_(model.info().nc), nf_(0) {
  if (!model.has_jacobians()) throw std::invalid_argument(missing_jacobians_message(model.info()));
  const ModelInfo& info = model.info();
  const std::vector<char> prescribed = prescribed_coordinates(model);
  for (int i = 0; i < m_; ++i)
    if (!prescribed[i]) free_.push_back(i);
  nf_ = static_cast<int>(free_.size());
  const size_t m = static_cast<size_t>(std::max(m_, 1)), nc = static_cast<size_t>(std::max(nc_, 1));
  const size_t nf = static_cast<size_t>(std::max(nf_, 1));
  udot_.assign(m, 0.0);
  lambda_.assign(nc, 0.0);
  tau0_.assign(static_cast<size_t>(std::max(info.ntau, 1)), 0.0);
  for (auto* v : {&dfdq_, &dfdu_, &dMa_, &dCl_, &M_}) v->assign(m * m, 0.0);
  L_.assign(nf * nf, 0.0);
  Y_.assign(nf * 2 * m, 0.0);
  C_.assign(nc * m, 0.0);
  W_.assign(nc * nf, 0.0);
  G_.assign(nc * nc, 0.0);
  z_.assign(nc, 0.0);
  used_.assign(nc, 0);
}

bool StateJacobian::accelerations(double t, const double* q, const double* u, const double* tau) {
  if (nc_ > 0) {
    if (model_.constrained_dynamics(t, q, u, tau, udot_.data(), lambda_.data()) == 0) return true;
    // At a singular position the generated solve gives up: the right-hand
    // side's own fallbacks (the augmented Lagrangian; they allocate, but
    // only there) give the udot and lambda the derivatives are taken at.
    return LoopSolver(model_).dynamics(t, q, u, tau, udot_.data(), lambda_.data()) == 0;
  }
  return model_.forward_dynamics(t, q, u, tau, udot_.data()) == 0;
}

// Cholesky factor L of the free block of M (lower triangle of L_).
bool StateJacobian::factor_mass_block(const double* q) {
  model_.mass_matrix(q, M_.data());
  const int n = nf_;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) L_[i * n + j] = M_[free_[i] * m_ + free_[j]];
  return detail::cholesky_factor(L_.data(), n);
}

void StateJacobian::solve_mass_block(double* v) const { detail::cholesky_solve(L_.data(), nf_, v); }

// G = C_F M_FF^-1 C_F^T in place as its Cholesky factor, rows that depend
// on earlier ones (redundant loop equations) marked unused, by the routine
// of LoopSolver's least-norm steps.
bool StateJacobian::factor_gram() {
  for (int i = 0; i < nc_; ++i) {
    double* w = &W_[static_cast<size_t>(i) * nf_];
    for (int a = 0; a < nf_; ++a) w[a] = C_[i * m_ + free_[a]];
    solve_mass_block(w);
  }
  for (int i = 0; i < nc_; ++i)
    for (int j = 0; j <= i; ++j) {
      double v = 0.0;
      for (int a = 0; a < nf_; ++a) v += C_[i * m_ + free_[a]] * W_[j * nf_ + a];
      G_[i * nc_ + j] = v;
    }
  return detail::factor_gram(G_.data(), nc_, used_.data());
}

// Each column y of Y (free rows) := y - M_FF^-1 C_F^T G^+ C_F y.
void StateJacobian::project_columns() {
  for (int k = 0; k < 2 * m_; ++k) {
    double* y = &Y_[static_cast<size_t>(k) * nf_];
    for (int i = 0; i < nc_; ++i) {
      double v = 0.0;
      for (int a = 0; a < nf_; ++a) v += C_[i * m_ + free_[a]] * y[a];
      z_[i] = v;
    }
    detail::cholesky_solve(G_.data(), nc_, z_.data(), used_.data());  // w = 0 on the dropped rows
    for (int i = 0; i < nc_; ++i)
      if (used_[i])
        for (int a = 0; a < nf_; ++a) y[a] -= W_[static_cast<size_t>(i) * nf_ + a] * z_[i];
  }
}

bool StateJacobian::evaluate(double t, const double* x, const double* tau, double* J) {
  const double* q = x;
  const double* u = x + m_;
  if (!tau) tau = tau0_.data();
  if (!accelerations(t, q, u, tau) || !factor_mass_block(q)) return false;
  model_.forcing_jacobian(t, q, u, tau, dfdq_.data(), dfdu_.data());
  model_.mass_matrix_product_jacobian(q, udot_.data(), dMa_.data());
  if (nc_ > 0) model_.constraint_force_jacobian(q, lambda_.data(), dCl_.data());
  // The free rows of the residual derivative, column by column (column-major Y).
  for (int k = 0; k < m_; ++k) {
    double* yq = &Y_[static_cast<size_t>(k) * nf_];
    double* yu = &Y_[static_cast<size_t>(m_ + k) * nf_];
    for (int a = 0; a < nf_; ++a) {
      const int row = free_[a] * m_ + k;
      yq[a] = dfdq_[row] - dMa_[row] + (nc_ > 0 ? dCl_[row] : 0.0);
      yu[a] = dfdu_[row];
    }
    solve_mass_block(yq);
    solve_mass_block(yu);
  }
  if (nc_ > 0) {
    model_.constraint_jacobian(q, C_.data());
    if (factor_gram()) project_columns();
  }
  const int n = 2 * m_;
  std::fill(J, J + static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < m_; ++i) J[i * n + m_ + i] = 1.0;  // q' = u
  for (int k = 0; k < n; ++k)
    for (int a = 0; a < nf_; ++a) J[(m_ + free_[a]) * n + k] = Y_[static_cast<size_t>(k) * nf_ + a];
  return true;
}

}  // namespace kanegen::runtime
