// SPDX-License-Identifier: MIT
#include "kanegen/runtime/loops.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kanegen/runtime/text.hpp"

namespace kanegen::runtime {

/// The mass matrix restricted to the coordinates that move, factored once:
/// corrections of least kinetic-energy norm (mass-orthogonal projection)
/// keep the motion on its branch through singular positions, where the
/// Euclidean least-norm step would redistribute it among the coordinates.
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
    for (int j = 0; j < m && ok_; ++j) {
      double s = L_[j * m + j];
      for (int k = 0; k < j; ++k) s -= L_[j * m + k] * L_[j * m + k];
      if (!(s > 0.0)) {
        ok_ = false;
        break;
      }
      L_[j * m + j] = std::sqrt(s);
      for (int i = j + 1; i < m; ++i) {
        double v = L_[i * m + j];
        for (int k = 0; k < j; ++k) v -= L_[i * m + k] * L_[j * m + k];
        L_[i * m + j] = v / L_[j * m + j];
      }
    }
  }
  bool ok() const { return ok_; }
  /// v (length nu, entries at cols) := M_cols^-1 v.
  void solve(double* v) const {
    const int m = static_cast<int>(cols_.size());
    std::vector<double> x(m);
    for (int i = 0; i < m; ++i) x[i] = v[cols_[i]];
    for (int i = 0; i < m; ++i) {
      for (int k = 0; k < i; ++k) x[i] -= L_[i * m + k] * x[k];
      x[i] /= L_[i * m + i];
    }
    for (int i = m - 1; i >= 0; --i) {
      for (int k = i + 1; k < m; ++k) x[i] -= L_[k * m + i] * x[k];
      x[i] /= L_[i * m + i];
    }
    for (int i = 0; i < m; ++i) v[cols_[i]] = x[i];
  }

 private:
  int n_;
  std::vector<int> cols_;
  std::vector<double> L_;
  bool ok_ = true;
};

namespace {

constexpr int kMaxNewton = 50;

/// x = A^T y with (A A^T) y = r, A the rows of C restricted to `cols`: the
/// least-norm solution of A x = r. Rows that are (numerically) combinations
/// of earlier ones get y = 0, so redundant loop equations (a parallelogram)
/// do not break it. Returns false if A has no usable row.
bool least_norm(const std::vector<double>& C, int nc, int nu, const std::vector<int>& cols,
                const std::vector<double>& r, std::vector<double>* x, const Metric* metric = nullptr) {
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
  std::vector<bool> used(nc, false);
  bool any = false;
  for (int j = 0; j < nc; ++j) {
    const double scale = G[j * nc + j];
    double s = scale;
    for (int k = 0; k < j; ++k)
      if (used[k]) s -= G[j * nc + k] * G[j * nc + k];
    if (!(s > 1e-12 * scale) || !(scale > 0.0)) continue;
    used[j] = any = true;
    const double l = std::sqrt(s);
    G[j * nc + j] = l;
    for (int i = j + 1; i < nc; ++i) {
      double v = G[i * nc + j];
      for (int k = 0; k < j; ++k)
        if (used[k]) v -= G[i * nc + k] * G[j * nc + k];
      G[i * nc + j] = v / l;
    }
  }
  std::vector<double> y(r);
  for (int i = 0; i < nc; ++i) {
    if (!used[i]) {
      y[i] = 0.0;
      continue;
    }
    for (int k = 0; k < i; ++k)
      if (used[k]) y[i] -= G[i * nc + k] * y[k];
    y[i] /= G[i * nc + i];
  }
  for (int i = nc - 1; i >= 0; --i) {
    if (!used[i]) continue;
    for (int k = i + 1; k < nc; ++k)
      if (used[k]) y[i] -= G[k * nc + i] * y[k];
    y[i] /= G[i * nc + i];
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

bool LoopSolver::close_positions(double* q, const std::vector<int>& moving, const Metric* metric,
                                 int* iterations, std::string* why) const {
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
    if (!least_norm(C, nc_, nu, moving, phi, &dx, metric)) {
      *why = "the loop equations do not depend on the coordinates that may move (" + describe(moving) + ")";
      return false;
    }
    // Damped when the step is large: long steps jump between branches.
    double size = 0.0;
    int largest = moving.empty() ? 0 : moving.front();
    for (int c : moving)
      if (std::abs(dx[c]) > size) {
        size = std::abs(dx[c]);
        largest = c;
      }
    // Drift after an integration step is tiny; a large correction means the
    // loop equations are nearly dependent here, where the projection could
    // move the motion onto another branch.
    if (metric && size > 1e-6) {
      *why = std::string("singular configuration: closing the loops would move ") +
             model_.info().coordinate_names[largest] + " by " + format_double(dx[largest]) +
             " after one step (the loop equations are nearly dependent: links in line, a dead point or a "
             "bifurcation)";
      return false;
    }
    const double damping = size > 0.5 ? 0.5 / size : 1.0;
    for (int c : moving) q[c] += damping * dx[c];
  }
  return false;
}

bool LoopSolver::close_speeds(const double* q, double* u, const std::vector<int>& moving,
                              const Metric* metric, std::string* why) const {
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
  if (!least_norm(C, nc_, nu, moving, r, &du, metric)) {
    *why = "the loop speeds do not depend on the speeds that may change";
    return false;
  }
  double size = 0.0, speed = 0.0;
  int largest = moving.empty() ? 0 : moving.front();
  for (int c : moving) {
    speed = std::max(speed, std::abs(u[c]));
    if (std::abs(du[c]) > size) {
      size = std::abs(du[c]);
      largest = c;
    }
  }
  if (metric && size > 1e-6 * (1.0 + speed)) {  // as for the positions: nearly dependent loop equations
    *why = std::string("singular configuration: closing the loops would change ") +
           model_.info().speed_names[largest] + " by " + format_double(du[largest]) +
           " after one step (the loop equations are nearly dependent: links in line, a dead point or a "
           "bifurcation)";
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
  if (!close_positions(q, free, nullptr, &a.iterations, &why) || !close_speeds(q, u, free, nullptr, &why))
    throw std::runtime_error("assembly failed: " + why + ", holding " + describe(a.independent) +
                             " at the given values; start " + configuration(q) +
                             ". Check the loop's lengths and points, or give initial values nearer a closed "
                             "configuration (\"initial\" in the model, or --q0)");
  a.residual = residual(q);
  return a;
}

bool LoopSolver::project(double* q, double* u, std::string* why) const {
  if (!active()) return true;
  std::vector<int> moving;
  for (int i = 0; i < nq_; ++i)
    if (model_.info().coordinate_roles[i] != 2) moving.push_back(i);
  const Metric metric(model_, q, moving);
  const Metric* m = metric.ok() ? &metric : nullptr;
  if (!close_positions(q, moving, m, nullptr, why) || !close_speeds(q, u, moving, m, why)) {
    *why += " at " + configuration(q);
    return false;
  }
  return true;
}

}  // namespace kanegen::runtime
