// SPDX-License-Identifier: MIT
#include "kanegen/runtime/loops.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cholesky.hpp"
#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {

namespace {

using detail::cholesky_factor;
using detail::cholesky_solve;
using detail::factor_gram;

}  // namespace

/// The mass matrix restricted to the coordinates `cols`, factored once (the
/// metric of Gauss's principle: accelerations of least kinetic-energy norm).
class Metric {
 public:
  Metric(const Model& model, const double* q, const std::vector<int>& cols)
      : n_(model.info().nu), cols_(cols) {
    std::vector<double> M(static_cast<size_t>(n_) * n_);
    model.mass_matrix(q, M.data());
    const int m = static_cast<int>(cols.size());
    L_.assign(static_cast<size_t>(m) * m, 0.0);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j <= i; ++j) L_[i * m + j] = M[cols[i] * n_ + cols[j]];
    ok_ = cholesky_factor(L_.data(), m);
  }
  bool ok() const { return ok_; }
  /// v (length nu, entries at cols) := M_cols^-1 v.
  void solve(double* v) const {
    const int m = static_cast<int>(cols_.size());
    std::vector<double> x(m);
    for (int i = 0; i < m; ++i) x[i] = v[cols_[i]];
    cholesky_solve(L_.data(), m, x.data());
    for (int i = 0; i < m; ++i) v[cols_[i]] = x[i];
  }

 private:
  int n_;
  std::vector<int> cols_;
  std::vector<double> L_;
  bool ok_ = true;
};

/// The mass-orthogonal projection of the augmented Lagrangian method
/// (Bayo and Ledesma 1996): a correction dx of the moving coordinates with
/// (M + alpha C^T C) dx = alpha C^T r, the minimum of
/// dx^T M dx + alpha |C dx - r|^2. Where the loop equations are independent
/// it meets C dx = r to 1e-7 per application (so a few applications close the
/// loops as Newton does); where they are nearly dependent (a singular
/// position) it moves the coordinates only as far as the equations hold
/// them, so round-off cannot push the motion onto another branch.
class Projector {
 public:
  Projector(const Model& model, const double* q, const std::vector<int>& cols)
      : nu_(model.info().nu), nc_(model.info().nc), cols_(cols) {
    std::vector<double> M(static_cast<size_t>(nu_) * nu_);
    model.mass_matrix(q, M.data());
    C_.resize(static_cast<size_t>(nc_) * nu_);
    model.constraint_jacobian(q, C_.data());
    const int m = static_cast<int>(cols.size());
    // alpha C^T C about 1e7 times M (the value Bayo and Ledesma use).
    double mass = 0.0, stiffness = 0.0;
    for (int i = 0; i < m; ++i) {
      mass = std::max(mass, M[cols[i] * nu_ + cols[i]]);
      for (int c = 0; c < nc_; ++c)
        stiffness = std::max(stiffness, C_[c * nu_ + cols[i]] * C_[c * nu_ + cols[i]]);
    }
    alpha_ = stiffness > 0.0 ? 1e7 * mass / stiffness : 0.0;
    L_.assign(static_cast<size_t>(m) * m, 0.0);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j <= i; ++j) {
        double v = M[cols[i] * nu_ + cols[j]];
        for (int c = 0; c < nc_; ++c) v += alpha_ * C_[c * nu_ + cols[i]] * C_[c * nu_ + cols[j]];
        L_[i * m + j] = v;
      }
    ok_ = alpha_ > 0.0 && cholesky_factor(L_.data(), m);
  }
  bool ok() const { return ok_; }
  /// x (nu; zero outside the moving columns) := the correction for r (nc).
  void correct(const double* r, double* x) const {
    const int m = static_cast<int>(cols_.size());
    std::vector<double> y(m, 0.0);
    for (int i = 0; i < m; ++i)
      for (int c = 0; c < nc_; ++c) y[i] += alpha_ * C_[c * nu_ + cols_[i]] * r[c];
    cholesky_solve(L_.data(), m, y.data());
    std::fill(x, x + nu_, 0.0);
    for (int i = 0; i < m; ++i) x[cols_[i]] = y[i];
  }

 private:
  int nu_, nc_;
  std::vector<int> cols_;
  std::vector<double> C_, L_;
  double alpha_ = 0.0;
  bool ok_ = false;
};

namespace {

constexpr int kMaxNewton = 50;
constexpr int kMaxAugmented = 20;  // iterations of the augmented Lagrangian
// The penalty of the augmented Lagrangian: alpha C^T C against M.
constexpr double kPenalty = 1e7;
// Below this ratio of pivots of C M^-1 C^T (the loop equations nearly
// dependent, within about 1e-4 rad of a parallelogram's singular position)
// the accelerations come from the augmented Lagrangian, whose loop forces
// stay bounded, instead of the solve with multipliers, which would amplify
// round-off into a change of branch.
constexpr double kWeakestRow = 1e-8;
// The largest |phi| the projection leaves after an integration step.
constexpr double kProjectedResidual = 1e-10;

/// What least_norm found about the rank of A W^-1 A^T.
struct LeastNormRank {
  int dropped = 0;       ///< rows skipped as combinations of earlier ones
  double weakest = 0.0;  ///< smallest pivot of a kept row over the largest diagonal entry
};

/// x = A^T y with (A A^T) y = r, A the rows of C restricted to `cols`: the
/// least-norm solution of A x = r. Rows that are (numerically) combinations
/// of earlier ones get y = 0, so redundant loop equations (a parallelogram)
/// do not break it. Returns false if A has no usable row.
bool least_norm(const std::vector<double>& C, int nc, int nu, const std::vector<int>& cols,
                const std::vector<double>& r, std::vector<double>* x, const Metric* metric = nullptr,
                double* multipliers = nullptr, LeastNormRank* rank = nullptr) {
  // W^-1 A^T, column by column (A^T itself without a metric).
  std::vector<double> WA(static_cast<size_t>(nc) * nu, 0.0);
  for (int i = 0; i < nc; ++i)
    for (int c : cols) WA[i * nu + c] = C[i * nu + c];
  if (metric)
    for (int i = 0; i < nc; ++i) metric->solve(&WA[static_cast<size_t>(i) * nu]);
  std::vector<double> G(static_cast<size_t>(nc) * nc, 0.0);  // A W^-1 A^T, then its Cholesky factor
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j <= i; ++j) {
      double v = 0.0;
      for (int c : cols) v += C[i * nu + c] * WA[j * nu + c];
      G[i * nc + j] = v;
    }
  std::vector<char> used(nc, 0);
  std::vector<double> diagonal(nc);
  for (int j = 0; j < nc; ++j) diagonal[j] = G[j * nc + j];
  const bool any = factor_gram(G.data(), nc, used.data());
  std::vector<double> y(r);
  cholesky_solve(G.data(), nc, y.data(), used.data());
  if (multipliers) std::copy(y.begin(), y.end(), multipliers);
  if (rank) {
    rank->dropped = static_cast<int>(std::count(used.begin(), used.end(), 0));
    double largest = 0.0, smallest = INFINITY;
    for (int j = 0; j < nc; ++j) largest = std::max(largest, diagonal[j]);
    for (int j = 0; j < nc; ++j)
      if (used[j]) smallest = std::min(smallest, G[j * nc + j] * G[j * nc + j]);
    rank->weakest = smallest / largest;
  }
  x->assign(nu, 0.0);
  for (int c : cols)
    for (int i = 0; i < nc; ++i) (*x)[c] += WA[i * nu + c] * y[i];
  return any;
}

/// The columns of C (among `cols`) that Gaussian elimination with complete
/// pivoting takes as pivots: the dependent coordinates that leave the
/// best-conditioned square block.
std::vector<int> pivot_columns(std::vector<double> C, int nc, int nu, const std::vector<int>& cols) {
  std::vector<int> chosen;
  std::vector<bool> row_done(nc, false), col_done(nu, false);
  double largest = 0.0;
  for (int i = 0; i < nc; ++i)
    for (int c : cols) largest = std::max(largest, std::abs(C[i * nu + c]));
  for (int step = 0; step < nc; ++step) {
    int pr = -1, pc = -1;
    double best = 0.0;
    for (int i = 0; i < nc; ++i) {
      if (row_done[i]) continue;
      for (int c : cols)
        if (!col_done[c] && std::abs(C[i * nu + c]) > best) {
          best = std::abs(C[i * nu + c]);
          pr = i;
          pc = c;
        }
    }
    if (pr < 0 || !(best > 1e-9 * largest)) break;  // the remaining rows are redundant
    row_done[pr] = col_done[pc] = true;
    chosen.push_back(pc);
    for (int i = 0; i < nc; ++i) {
      if (row_done[i]) continue;
      const double factor = C[i * nu + pc] / C[pr * nu + pc];
      for (int c : cols) C[i * nu + c] -= factor * C[pr * nu + c];
    }
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

}  // namespace

LoopSolver::LoopSolver(const Model& model, double tolerance)
    : model_(model), nc_(model.info().nc), nq_(model.info().nq), tolerance_(tolerance) {}

double LoopSolver::residual(const double* q, int* row) const {
  std::vector<double> phi(std::max(nc_, 1), 0.0);
  model_.constraints(q, phi.data());
  double worst = 0.0;
  for (int i = 0; i < nc_; ++i)
    if (!(std::abs(phi[i]) <= worst)) {  // NaN counts as the worst
      worst = std::isnan(phi[i]) ? phi[i] : std::abs(phi[i]);
      if (row) *row = i;
      if (std::isnan(worst)) break;
    }
  return worst;
}

std::string LoopSolver::configuration(const double* q) const {
  std::string s = "q=[";
  for (int i = 0; i < nq_; ++i) s += (i ? ", " : "") + format_double(q[i]);
  return s + "]";
}

std::string LoopSolver::describe(const std::vector<int>& coordinates) const {
  std::string s;
  for (int c : coordinates) s += (s.empty() ? "" : ", ") + std::string(model_.info().coordinate_names[c]);
  return s.empty() ? "none" : s;
}

bool LoopSolver::close_positions(double* q, const std::vector<int>& moving, int* iterations,
                                 std::string* why) const {
  const int nu = model_.info().nu;
  std::vector<double> phi(nc_), C(static_cast<size_t>(nc_) * nu), dx;
  double previous = INFINITY;
  for (int it = 0; it <= kMaxNewton; ++it) {
    int row = 0;
    const double r = residual(q, &row);
    if (r <= tolerance_) {
      if (iterations) *iterations = it;
      return true;
    }
    // Newton converges quadratically near a closed configuration; a
    // residual that stops falling means there is none nearby.
    if (it == kMaxNewton || !(r < previous || it < 8)) {
      *why = "the loops do not close: |phi| stays at " + format_double(r) + " in '" +
             model_.info().constraint_names[row] + "' after " + std::to_string(it) + " Newton steps";
      return false;
    }
    previous = r;
    model_.constraints(q, phi.data());
    model_.constraint_jacobian(q, C.data());
    for (double& v : phi) v = -v;
    if (!least_norm(C, nc_, nu, moving, phi, &dx)) {
      *why = "the loop equations do not depend on the coordinates that may move (" + describe(moving) + ")";
      return false;
    }
    // Damped when the step is large: long steps jump between branches.
    double size = 0.0;
    for (int c : moving) size = std::max(size, std::abs(dx[c]));
    const double damping = size > 0.5 ? 0.5 / size : 1.0;
    for (int c : moving) q[c] += damping * dx[c];
  }
  return false;
}

bool LoopSolver::close_speeds(const double* q, double* u, const std::vector<int>& moving,
                              std::string* why) const {
  const int nu = model_.info().nu;
  std::vector<double> C(static_cast<size_t>(nc_) * nu), r(nc_, 0.0), du;
  model_.constraint_jacobian(q, C.data());
  bool holds = true;  // C u = 0 to round-off already: leave u alone
  for (int i = 0; i < nc_; ++i) {
    double scale = 0.0;
    for (int k = 0; k < nu; ++k) {
      r[i] -= C[i * nu + k] * u[k];
      scale += std::abs(C[i * nu + k] * u[k]);
    }
    holds = holds && std::abs(r[i]) <= 1e-13 * scale;
  }
  if (holds) return true;
  if (!least_norm(C, nc_, nu, moving, r, &du)) {
    *why = "the loop speeds do not depend on the speeds that may change";
    return false;
  }
  for (int c : moving) u[c] += du[c];
  return true;
}

Assembly LoopSolver::assemble(double* q, double* u) const {
  Assembly a;
  if (!active()) return a;
  const ModelInfo& info = model_.info();
  std::vector<int> free, held;
  for (int i = 0; i < nq_; ++i) {
    if (info.coordinate_roles[i] == 1) a.independent.push_back(i);
    if (info.coordinate_roles[i] == 0) free.push_back(i);
  }
  if (a.independent.empty()) {
    // The dependent coordinates are the pivots of C at the given state.
    std::vector<double> C(static_cast<size_t>(nc_) * info.nu);
    model_.constraint_jacobian(q, C.data());
    const std::vector<int> dependent = pivot_columns(C, nc_, info.nu, free);
    for (int c : free)
      if (!std::binary_search(dependent.begin(), dependent.end(), c)) a.independent.push_back(c);
    free = dependent;
    a.picked = true;
  }
  std::string why;
  if (!close_positions(q, free, &a.iterations, &why) || !close_speeds(q, u, free, &why))
    throw std::runtime_error("assembly failed: " + why + ", holding " + describe(a.independent) +
                             " at the given values; start " + configuration(q) +
                             ". Check the loop's lengths and points, or give initial values nearer a closed "
                             "configuration (\"initial\" in the model, or --q0)");
  a.residual = residual(q);
  return a;
}

int LoopSolver::dynamics(double t, const double* q, const double* u, const double* tau, double* udot,
                         double* lambda) const {
  const int status = model_.constrained_dynamics(t, q, u, tau, udot, lambda);
  if (status >= 0 || !active()) return status;
  // A prescribed speed's acceleration is known only inside the generated code.
  for (int i = 0; i < nq_; ++i)
    if (model_.info().coordinate_roles[i] == 2) return status;
  std::vector<int> all(nq_);
  for (int i = 0; i < nq_; ++i) all[i] = i;
  // Where a fallback cannot be used either, the generated solve's -k stands:
  // the loop equations are what failed, not a pivot of M.
  const Metric metric(model_, q, all);
  if (!metric.ok()) return status;
  if (scaled_dynamics(t, q, u, tau, metric, udot, lambda)) return 0;
  return augmented_dynamics(t, q, u, tau, udot, lambda) ? 0 : status;
}

bool LoopSolver::scaled_dynamics(double t, const double* q, const double* u, const double* tau,
                                 const Metric& metric, double* udot, double* lambda) const {
  const int nu = model_.info().nu;
  std::vector<int> all(nq_);
  for (int i = 0; i < nq_; ++i) all[i] = i;
  std::vector<double> C(static_cast<size_t>(nc_) * nu), r(nc_), correction;
  model_.forcing(t, q, u, tau, udot);
  metric.solve(udot);  // the acceleration without the loops
  model_.constraint_jacobian(q, C.data());
  model_.constraint_bias(q, u, r.data());
  for (int c = 0; c < nc_; ++c)
    for (int i = 0; i < nu; ++i) r[c] -= C[c * nu + i] * udot[i];
  // The generated solve gives up when a pivot is small against the largest
  // row; least_norm judges each row against its own size, which is what a
  // row that merely shrinks near the singular position needs (a
  // parallelogram's x rows scale with the sine of the crank angle).
  LeastNormRank rank;
  if (!least_norm(C, nc_, nu, all, r, &correction, &metric, lambda, &rank) || rank.dropped > 0 ||
      !(rank.weakest > kWeakestRow))
    return false;
  for (int i = 0; i < nu; ++i) udot[i] += correction[i];
  return true;
}

bool LoopSolver::augmented_dynamics(double t, const double* q, const double* u, const double* tau,
                                    double* udot, double* lambda) const {
  const int nu = model_.info().nu;
  std::vector<double> W(static_cast<size_t>(nu) * nu), f(nu), C(static_cast<size_t>(nc_) * nu), gamma(nc_);
  model_.mass_matrix(q, W.data());
  model_.forcing(t, q, u, tau, f.data());
  model_.constraint_jacobian(q, C.data());
  model_.constraint_bias(q, u, gamma.data());
  // The penalty alpha makes alpha C^T C about 1e7 times M on the rows that
  // constrain (Bayo and Ledesma's value for unit-scale models): a few
  // iterations meet the independent loop equations, W = M + alpha C^T C
  // stays well conditioned, and the rows that (nearly) vanish at the
  // singular position bend the motion only as far as they can hold it,
  // with bounded forces, instead of deciding the branch from round-off.
  double mass = 0.0, stiffness = 0.0;
  for (int i = 0; i < nu; ++i) {
    mass = std::max(mass, W[i * nu + i]);
    for (int c = 0; c < nc_; ++c) stiffness = std::max(stiffness, C[c * nu + i] * C[c * nu + i]);
  }
  const double alpha = stiffness > 0.0 ? kPenalty * mass / stiffness : 0.0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j <= i; ++j)
      for (int c = 0; c < nc_; ++c) W[i * nu + j] += alpha * C[c * nu + i] * C[c * nu + j];
  if (!cholesky_factor(W.data(), nu)) return false;
  // W udot_k = f + C^T (lambda_k + alpha gamma), then
  // lambda_{k+1} = lambda_k - alpha (C udot_k - gamma), so that
  // M udot_k = f + C^T lambda_{k+1}.
  std::fill(lambda, lambda + nc_, 0.0);
  std::vector<double> violation(nc_);
  for (int iteration = 0; iteration < kMaxAugmented; ++iteration) {
    for (int i = 0; i < nu; ++i) {
      udot[i] = f[i];
      for (int c = 0; c < nc_; ++c) udot[i] += C[c * nu + i] * (lambda[c] + alpha * gamma[c]);
    }
    cholesky_solve(W.data(), nu, udot);
    double worst = 0.0, scale = 0.0;
    for (int c = 0; c < nc_; ++c) {
      violation[c] = -gamma[c];
      for (int i = 0; i < nu; ++i) {
        violation[c] += C[c * nu + i] * udot[i];
        scale = std::max(scale, std::abs(C[c * nu + i] * udot[i]));
      }
      worst = std::max(worst, std::abs(violation[c]));
    }
    // M udot = f + C^T lambda_{k+1}: the multipliers of the udot just solved.
    for (int c = 0; c < nc_; ++c) lambda[c] -= alpha * violation[c];
    if (worst <= 1e-12 * std::max(scale, 1e-300)) break;
  }
  return true;
}

bool LoopSolver::project(double* q, double* u, std::string* why) const {
  if (!active()) return true;
  std::vector<int> moving;
  for (int i = 0; i < nq_; ++i)
    if (model_.info().coordinate_roles[i] != 2) moving.push_back(i);
  const Projector projector(model_, q, moving);
  if (!projector.ok()) {  // M is not positive definite here: the Euclidean least-norm steps
    if (close_positions(q, moving, nullptr, why) && close_speeds(q, u, moving, why)) return true;
    *why += " at " + configuration(q);
    return false;
  }
  const int nu = model_.info().nu;
  std::vector<double> r(nc_), dx(nu), C(static_cast<size_t>(nc_) * nu);
  // Positions: modified Newton with the projector of the start, until the
  // residual is at the tolerance or stops falling.
  double previous = INFINITY;
  int row = 0;
  for (int it = 0; it < kMaxNewton; ++it) {
    const double residual_now = residual(q, &row);
    if (residual_now <= tolerance_ || !(residual_now < 0.5 * previous)) break;
    previous = residual_now;
    model_.constraints(q, r.data());
    for (double& v : r) v = -v;
    projector.correct(r.data(), dx.data());
    for (int c : moving) q[c] += dx[c];
  }
  if (const double left = residual(q, &row); !(left <= kProjectedResidual)) {
    *why = std::string("the loops cannot be kept closed: |phi| stays at ") + format_double(left) + " in '" +
           model_.info().constraint_names[row] +
           "' (the loop equations are dependent here: links in line, a dead point or a bifurcation, where "
           "the motion could take either branch) at " +
           configuration(q);
    return false;
  }
  // Speeds: C u = 0 by the same projection, two applications (each leaves
  // 1e-7 of the violation where the equations are independent).
  model_.constraint_jacobian(q, C.data());
  for (int pass = 0; pass < 2; ++pass) {
    for (int c = 0; c < nc_; ++c) {
      r[c] = 0.0;
      for (int k = 0; k < nu; ++k) r[c] -= C[c * nu + k] * u[k];
    }
    projector.correct(r.data(), dx.data());
    for (int c : moving) u[c] += dx[c];
  }
  return true;
}

}  // namespace kanegen::runtime
