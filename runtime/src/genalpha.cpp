// SPDX-License-Identifier: MIT
#include "kanegen/runtime/genalpha.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "cholesky.hpp"
#include "envelope_lu.hpp"

namespace kanegen::runtime {
namespace {

using detail::cholesky_factor;
using detail::cholesky_solve;
using detail::envelope_lu_solve;
using detail::envelope_multiply;
using detail::factor_gram;
using detail::lu_factor;
using detail::prepare_solve;
using detail::row_envelopes;

/// Within a step, a contraction rate above this with a stale iteration
/// matrix re-evaluates the Jacobians; above kRefreshNext at the end of a
/// step, the next step starts with fresh ones.
constexpr double kRefreshNow = 0.5;
constexpr double kRefreshNext = 0.1;
/// The smallest contraction rate theta / (1 - theta) a first Newton
/// iteration is trusted with (see GenAlpha::step).
constexpr double kMinRate = 1e-3;
/// The position residual the start needs (the explicit path's guarantee).
constexpr double kStartResidual = 1e-10;

/// Numbers in messages: ten digits are enough to read and to locate.
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

/// *reason = text; false.
bool refuse(std::string* reason, const char* text) {
  *reason = text;
  return false;
}

bool all_finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

GenAlphaCoefficients genalpha_coefficients(double rho_inf) {
  GenAlphaCoefficients c{};
  c.alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  c.alpha_f = rho_inf / (rho_inf + 1.0);
  c.gamma = 0.5 + c.alpha_f - c.alpha_m;
  c.beta = 0.25 * (c.gamma + 0.5) * (c.gamma + 0.5);
  return c;
}

GenAlpha::GenAlpha(const Model& model, const GenAlphaOptions& options)
    : model_(model), opt_(options), c_(genalpha_coefficients(options.rho_inf)) {
  if (!(opt_.h > 0.0) || !std::isfinite(opt_.h))
    throw std::invalid_argument("genalpha: the step h must be > 0");
  if (!(opt_.rho_inf >= 0.0 && opt_.rho_inf <= 1.0))
    throw std::invalid_argument("genalpha: rho_inf must be in [0, 1]");
  if (opt_.max_newton < 1) throw std::invalid_argument("genalpha: max_newton must be >= 1");
  if (!(opt_.tolerance > 0.0) || !(opt_.constraint_tolerance > 0.0))
    throw std::invalid_argument("genalpha: the Newton tolerances must be > 0");
  if (!model.has_jacobians())
    throw std::invalid_argument(std::string("genalpha: model ") + model.info().name +
                                " has no Jacobian kernels; regenerate it with kanegen generate --jacobians");
  const ModelInfo& info = model.info();
  if (info.nq != info.nu) throw std::invalid_argument("genalpha: needs q_dot = u (nq == nu)");
  n_dof_ = info.nu;
  nc_ = info.nc;
  dim_ = n_dof_ + nc_;
  fused_ = nc_ == 0;
  const double h = opt_.h;
  beta_p_ = (1.0 - c_.alpha_m) / (h * h * c_.beta * (1.0 - c_.alpha_f));
  gamma_p_ = c_.gamma / (h * c_.beta);

  const size_t n = static_cast<size_t>(n_dof_), nc = static_cast<size_t>(nc_),
               dim = static_cast<size_t>(dim_);
  for (auto* v : {&q_, &u_, &vd_, &a_, &q1_, &u1_, &vd1_, &a1_, &f_, &given_}) v->assign(n, 0.0);
  for (auto* v : {&lam_, &lam1_, &phi_, &given_lambda_, &y_}) v->assign(std::max<size_t>(nc, 1), 0.0);
  for (auto* v : {&M_, &dfdq_, &dfdu_, &dMa_, &dCl_, &chol_}) v->assign(n * n, 0.0);
  prescribed_.assign(n, 0);
  if (info.coordinate_roles) {
    for (int i = 0; i < n_dof_; ++i) prescribed_[i] = info.coordinate_roles[i] == 2;
  } else if (nc_ == 0) {  // generated models with loops always have roles
    detect_prescribed();
  }
  for (int i = 0; i < n_dof_; ++i) {
    if (prescribed_[i])
      any_prescribed_ = true;
    else
      free_.push_back(i);
  }
  C_.assign(std::max<size_t>(nc * n, 1), 0.0);
  w_.assign(std::max<size_t>(nc * n, 1), 0.0);
  g_.assign(std::max<size_t>(nc * nc, 1), 0.0);
  used_.assign(std::max<size_t>(nc, 1), 0);
  rhs_.assign(dim, 0.0);
  lu_.assign(dim * dim, 0.0);
  lut_.assign(dim * dim, 0.0);
  pivots_.assign(dim, 0);
  lu_upper_begin_.assign(dim, 0);
  lu_lower_end_.assign(dim, 0);
  mass_begin_.assign(n, 0);
  mass_end_.assign(n, 0);
  no_inputs_.assign(static_cast<size_t>(std::max(info.ntau, 1)), 0.0);
}

std::string GenAlpha::state() const {
  const ModelInfo& info = model_.info();
  std::string s = "[";
  for (int i = 0; i < n_dof_; ++i)
    s += (i ? ", " : "") + std::string(info.coordinate_names[i]) + "=" + number(q_[i]);
  for (int i = 0; i < n_dof_; ++i) s += ", " + std::string(info.speed_names[i]) + "=" + number(u_[i]);
  return s + "]";
}

void GenAlpha::detect_prescribed() {
  const int n = n_dof_;
  std::vector<double> q(n), u(n), udot(n), tau(std::max(model_.info().ntau, 1), 0.0);
  for (int trial = 0; trial < 2; ++trial) {
    // A generic state near the initial one, where a driving force vanishes
    // only by accident (and then, at both states, the motion is free anyway).
    model_.initial_state(q.data(), u.data());
    for (int i = 0; i < n; ++i) {
      q[i] += 0.01 * std::sin(1.3 * i + 0.7 * trial + 1.0);
      u[i] += 0.1 * std::cos(0.9 * i + 1.1 * trial + 0.5);
    }
    const double t = 0.37 + 0.61 * trial;
    if (model_.forward_dynamics(t, q.data(), u.data(), tau.data(), udot.data()) != 0) continue;
    model_.mass_matrix(q.data(), M_.data());
    model_.forcing(t, q.data(), u.data(), tau.data(), f_.data());
    for (int i = 0; i < n; ++i) {
      double r = -f_[i], scale = std::abs(f_[i]);
      for (int j = 0; j < n; ++j) {
        r += M_[i * n + j] * udot[j];
        scale += std::abs(M_[i * n + j] * udot[j]);
      }
      if (std::abs(r) > 1e-8 * scale) prescribed_[i] = 1;  // LDL^T solves a free row to round-off
    }
  }
}

bool GenAlpha::fail(const std::string& reason, std::string* why) {
  if (why) *why = reason;
  return false;
}

double GenAlpha::constraint_residual(const double* q) {
  if (nc_ == 0) return 0.0;
  model_.constraints(q, phi_.data());
  double worst = 0.0;
  for (int i = 0; i < nc_; ++i) {
    if (std::isnan(phi_[i])) return phi_[i];
    worst = std::max(worst, std::abs(phi_[i]));
  }
  return worst;
}

bool GenAlpha::start(double t0, const double* q, const double* u, const double* tau, std::string* why) {
  if (!tau) tau = no_inputs_.data();
  started_ = false;
  factored_ = false;
  refresh_next_ = false;
  eta_ = 1.0;
  t0_ = t0;
  n_ = 0;
  std::copy(q, q + n_dof_, q_.begin());
  std::copy(u, u + n_dof_, u_.begin());
  // Messages are built only on failure: a start allocates nothing either.
  const auto failed = [&](const std::string& what) {
    return fail("genalpha: at t = " + number(t0) + ": " + what, why);
  };
  const double residual = constraint_residual(q_.data());
  if (!(residual <= kStartResidual))
    return failed("the initial positions do not close the loops (max |Phi| = " + number(residual) +
                  "); assemble them first");
  std::string reason;
  if (!correct_speeds(q_.data(), u_.data(), &reason)) return failed(reason);
  std::fill(lam_.begin(), lam_.end(), 0.0);
  const int status = model_.constrained_dynamics(t0, q_.data(), u_.data(), tau, vd_.data(), lam_.data());
  if (status > 0)
    return failed("the mass matrix is singular (pivot " + std::to_string(status) +
                  ") in the initial acceleration");
  if (status < 0)
    return failed("singular configuration (loop equation " + std::to_string(-status) +
                  ") in the initial acceleration");
  if (!all_finite(q_) || !all_finite(u_) || !all_finite(vd_))
    return failed("the initial state or acceleration is not finite");
  a_ = vd_;  // the consistent start of Arnold and Bruls: a_0 = udot_0
  started_ = true;
  return true;
}

void GenAlpha::predict(double t1, const double* tau) {
  std::copy(vd_.begin(), vd_.end(), vd1_.begin());
  std::copy(lam_.begin(), lam_.end(), lam1_.begin());
  if (any_prescribed_) {  // forward_dynamics sets the given accelerations whatever q and u
    model_.constrained_dynamics(t1, q_.data(), u_.data(), tau, given_.data(), given_lambda_.data());
    for (int i = 0; i < n_dof_; ++i)
      if (prescribed_[i]) vd1_[i] = given_[i];
  }
  const double h = opt_.h, am = c_.alpha_m, af = c_.alpha_f;
  for (int i = 0; i < n_dof_; ++i) {
    a1_[i] = (af * vd_[i] + (1.0 - af) * vd1_[i] - am * a_[i]) / (1.0 - am);
    q1_[i] = q_[i] + h * u_[i] + h * h * ((0.5 - c_.beta) * a_[i] + c_.beta * a1_[i]);
    u1_[i] = u_[i] + h * ((1.0 - c_.gamma) * a_[i] + c_.gamma * a1_[i]);
  }
}

bool GenAlpha::residual(double t1, const double* tau, std::string* reason) {
  const int n = n_dof_;
  if (fused_) {
    // One kernel for M and f: f_ := M^-1 f - udot, the prescribed rows 0
    // (forward_dynamics gives their accelerations, which predict() set).
    const int status = model_.forward_dynamics(t1, q1_.data(), u1_.data(), tau, f_.data());
    if (status != 0) {
      *reason = "the mass matrix is singular (pivot " + std::to_string(status) + ") at the trial state";
      return false;
    }
    for (int i = 0; i < n; ++i) f_[i] = prescribed_[i] ? 0.0 : f_[i] - vd1_[i];
    return true;
  }
  model_.mass_matrix(q1_.data(), M_.data());
  model_.forcing(t1, q1_.data(), u1_.data(), tau, f_.data());
  if (nc_ > 0) {
    model_.constraint_jacobian(q1_.data(), C_.data());
    model_.constraints(q1_.data(), phi_.data());
  }
  // rhs = f + C^T lambda - M udot, column by column: M is symmetric, so its
  // rows serve as columns, and the updates are independent (vectorized)
  // instead of one chain of dependent additions per row.
  std::copy(f_.begin(), f_.end(), rhs_.begin());
  for (int j = 0; j < n; ++j) {
    const double v = vd1_[j];
    const double* column = &M_[static_cast<size_t>(j) * n];
    for (int i = 0; i < n; ++i) rhs_[i] -= column[i] * v;
  }
  for (int k = 0; k < nc_; ++k) {
    const double l = lam1_[k];
    const double* row = &C_[static_cast<size_t>(k) * n];
    for (int i = 0; i < n; ++i) rhs_[i] += row[i] * l;
  }
  for (int i = 0; i < n; ++i)
    if (prescribed_[i]) rhs_[i] = 0.0;  // its row is the driving force, not an equation
  for (int k = 0; k < nc_; ++k) rhs_[n + k] = -beta_p_ * phi_[k];
  return true;
}

void GenAlpha::weight_residual() {
  if (!fused_) return;
  // f - M udot = M (M^-1 f - udot), with M from the last refresh: exact for
  // a constant M, otherwise part of the simplified Newton iteration's
  // approximation, like the kept iteration matrix.
  envelope_multiply(M_.data(), n_dof_, mass_begin_.data(), mass_end_.data(), f_.data(), rhs_.data());
  for (int i = 0; i < n_dof_; ++i)
    if (prescribed_[i]) rhs_[i] = 0.0;
}

bool GenAlpha::refresh(double t1, const double* tau) {
  const int n = n_dof_, dim = dim_;
  if (fused_) {  // residual() has not evaluated M
    model_.mass_matrix(q1_.data(), M_.data());
    // The prescribed rows and columns go: their residuals are 0 and their
    // rows no equations (the iteration matrix drops them too), and a hub's
    // column would otherwise widen every row's range to the full width.
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (prescribed_[i] || prescribed_[j]) M_[static_cast<size_t>(i) * n + j] = 0.0;
    row_envelopes(M_.data(), n, mass_begin_.data(), mass_end_.data());
  }
  model_.forcing_jacobian(t1, q1_.data(), u1_.data(), tau, dfdq_.data(), dfdu_.data());
  model_.mass_matrix_product_jacobian(q1_.data(), vd1_.data(), dMa_.data());
  if (nc_ > 0) model_.constraint_force_jacobian(q1_.data(), lam1_.data(), dCl_.data());
  ++stats_.jacobian_evaluations;
  // In the unknowns (udot, -lambda), with the constraint rows times beta':
  // [M + (gamma' C_t + K_t) / beta'  C^T; C  0], C_t = -df/du,
  // K_t = -df/dq + d(M udot)/dq - d(C^T lambda)/dq; every block O(1) as h -> 0.
  for (int i = 0; i < n; ++i) {
    double* row = &lu_[static_cast<size_t>(i) * dim];
    if (prescribed_[i]) {
      std::fill(row, row + dim, 0.0);
      row[i] = 1.0;
      continue;
    }
    for (int j = 0; j < n; ++j) {
      const size_t ij = static_cast<size_t>(i) * n + j;
      const double kt = -dfdq_[ij] + dMa_[ij] - (nc_ > 0 ? dCl_[ij] : 0.0);
      row[j] = M_[ij] + (-gamma_p_ * dfdu_[ij] + kt) / beta_p_;
    }
    for (int k = 0; k < nc_; ++k) row[n + k] = C_[k * n + i];
  }
  for (int k = 0; k < nc_; ++k) {
    double* row = &lu_[static_cast<size_t>(n + k) * dim];
    std::copy(&C_[static_cast<size_t>(k) * n], &C_[static_cast<size_t>(k) * n] + n, row);
    std::fill(row + n, row + dim, 0.0);
  }
  // A prescribed coordinate's column goes too (its increment is 0): with
  // only its row's 1 left, pivoting cannot mix it into the other rows, and
  // the solve gives exactly 0 instead of round-off of the size of the
  // elastic accelerations, which fed back through the hub and grew.
  for (int j = 0; j < n; ++j)
    if (prescribed_[j])
      for (int i = 0; i < dim; ++i) lu_[static_cast<size_t>(i) * dim + j] = i == j ? 1.0 : 0.0;
  ++stats_.factorizations;
  int column = 0;
  factored_ = lu_factor(lu_.data(), dim, pivots_.data(), &column);
  if (factored_) prepare_solve(lu_.data(), dim, lut_.data(), lu_upper_begin_.data(), lu_lower_end_.data());
  return factored_;
}

double GenAlpha::apply_increment() {
  const int n = n_dof_;
  const double h = opt_.h, scale = (1.0 - c_.alpha_f) / (1.0 - c_.alpha_m), tol = opt_.tolerance;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double da = scale * rhs_[i];
    const double dq = h * h * c_.beta * da, du = h * c_.gamma * da;
    vd1_[i] += rhs_[i];
    a1_[i] += da;
    q1_[i] += dq;
    u1_[i] += du;
    const double sq = dq / (tol * (1.0 + std::abs(q1_[i]))), su = du / (tol * (1.0 + std::abs(u1_[i])));
    sum += sq * sq + su * su;
  }
  for (int k = 0; k < nc_; ++k) lam1_[k] -= rhs_[n + k];
  return std::sqrt(sum / (2.0 * std::max<size_t>(free_.size(), 1)));
}

bool GenAlpha::correct_speeds(const double* q, double* u, std::string* reason) {
  if (nc_ == 0) return true;
  const int n = n_dof_, m = static_cast<int>(free_.size());
  model_.mass_matrix(q, M_.data());
  model_.constraint_jacobian(q, C_.data());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) chol_[i * m + j] = M_[free_[i] * n + free_[j]];
  if (!cholesky_factor(chol_.data(), m))
    return refuse(reason, "the mass matrix of the free coordinates is not positive definite");
  // w_k = M_ff^-1 C_kf^T, G = C_f M_ff^-1 C_f^T, y = G^-1 (C u): the change
  // -M_ff^-1 C_f^T y of least kinetic energy with C u = 0. Dependent rows
  // of G (redundant loop equations) are dropped.
  for (int k = 0; k < nc_; ++k) {
    double* wk = &w_[static_cast<size_t>(k) * n];
    for (int i = 0; i < m; ++i) wk[i] = C_[k * n + free_[i]];
    cholesky_solve(chol_.data(), m, wk);
    y_[k] = 0.0;
    for (int j = 0; j < n; ++j) y_[k] += C_[k * n + j] * u[j];
  }
  for (int k = 0; k < nc_; ++k)
    for (int l = 0; l <= k; ++l) {
      double s = 0.0;
      for (int i = 0; i < m; ++i) s += C_[k * n + free_[i]] * w_[static_cast<size_t>(l) * n + i];
      g_[k * nc_ + l] = s;
    }
  factor_gram(g_.data(), nc_, used_.data());
  cholesky_solve(g_.data(), nc_, y_.data(), used_.data());
  for (int k = 0; k < nc_; ++k)
    for (int i = 0; i < m; ++i) u[free_[i]] -= w_[static_cast<size_t>(k) * n + i] * y_[k];
  return true;
}

bool GenAlpha::newton(double t1, const double* tau, std::string* reason) {
  bool stale = factored_ && opt_.reuse_jacobian && !refresh_next_;
  bool refresh_now = !stale;
  // The first iteration's error estimate needs a contraction rate: that of
  // the last step's first iteration, at least kMinRate (RADAU5 takes the
  // last one, which quadratic convergence makes too optimistic here).
  const double eta_start = std::max(eta_, kMinRate);
  double eta = eta_start, previous = -1.0, theta = 0.0, theta_first = -1.0, theta_max = 0.0;
  double norm = 0.0, worst = 0.0;
  for (int iteration = 0; iteration < opt_.max_newton; ++iteration) {
    if (!residual(t1, tau, reason)) return false;
    if (!all_finite(fused_ ? f_ : rhs_)) return refuse(reason, "the residual is not finite");
    if (refresh_now) {
      if (!refresh(t1, tau)) return refuse(reason, "the iteration matrix is singular");
      refresh_now = stale = false;
    }
    weight_residual();
    envelope_lu_solve(lut_.data(), dim_, pivots_.data(), lu_upper_begin_.data(), lu_lower_end_.data(),
                      rhs_.data());
    norm = apply_increment();
    ++stats_.newton_iterations;
    if (!std::isfinite(norm)) return refuse(reason, "the Newton increment is not finite");
    if (previous >= 0.0) {
      theta = norm / previous;
      eta = theta < 1.0 ? theta / (1.0 - theta) : INFINITY;
      if (theta_first < 0.0) theta_first = theta;
      theta_max = std::max(theta_max, theta);
    }
    previous = norm;
    worst = constraint_residual(q1_.data());
    if (eta * norm <= 1.0 && worst <= opt_.constraint_tolerance) {
      if (theta_first >= 0.0) eta_ = theta_first < 1.0 ? theta_first / (1.0 - theta_first) : 1.0;
      refresh_next_ = theta_max > kRefreshNext;
      return true;
    }
    // Slow with an old matrix, or half the iterations spent: fresh Jacobians at this iterate,
    if (stale && (theta > kRefreshNow || iteration + 1 >= opt_.max_newton / 2)) {
      refresh_now = true;
      if (theta >= 1.0) {  // or, if it diverged, at the predictor again
        predict(t1, tau);
        previous = -1.0;
        eta = eta_start;
      }
    }
  }
  refresh_next_ = true;
  *reason = "Newton did not converge in " + std::to_string(opt_.max_newton) + " iterations (last increment " +
            number(norm * opt_.tolerance) + " relative, contraction " + number(theta) + ", max |Phi| " +
            number(worst) + "); a smaller step h may help";
  return false;
}

bool GenAlpha::step(const double* tau, std::string* why) {
  if (!started_) return fail("genalpha: step() before a successful start()", why);
  if (!tau) tau = no_inputs_.data();
  const double t1 = t0_ + static_cast<double>(n_ + 1) * opt_.h;
  predict(t1, tau);
  std::string reason;
  bool ok = newton(t1, tau, &reason) && correct_speeds(q1_.data(), u1_.data(), &reason);
  if (ok && (!all_finite(q1_) || !all_finite(u1_))) {
    reason = "the state is not finite";
    ok = false;
  }
  if (!ok) {
    ++stats_.rejected;
    return fail("genalpha: step from t = " + number(t()) + " to " + number(t1) + " failed: " + reason +
                    "; the state at t = " + number(t()) + " is " + state(),
                why);
  }
  q_.swap(q1_);  // commit
  u_.swap(u1_);
  vd_.swap(vd1_);
  a_.swap(a1_);
  lam_.swap(lam1_);
  ++n_;
  ++stats_.steps;
  return true;
}

}  // namespace kanegen::runtime
