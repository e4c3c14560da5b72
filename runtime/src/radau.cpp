// SPDX-License-Identifier: MIT
// Radau IIA of order 5 for x' = f(t, x), after Hairer and Wanner's RADAU5
// (Solving ODEs II, section IV.8): the 3-stage collocation method, stiffly
// accurate and L-stable. Each step solves for the stage increments Z by a
// simplified Newton iteration in the coordinates W = T^-1 Z that
// block-diagonalize the method's matrix: one real system with
// (mu_r/h I - J) and one complex one with (mu_c/h I - J), n x n each.
// The error estimate is the embedded order-3 solution filtered by
// (mu_r/h I - J)^-1; the step size follows Gustafsson's predictive
// controller. J and its LU factors are kept from step to step while Newton
// converges fast and h does not change. Closed loops are projected after
// each accepted step (opt.project), before the next step starts from it.
// Dense output is the collocation polynomial, which also predicts the next
// step's Newton start. All storage is sized by the constructor: a step
// allocates nothing unless it fails and builds its message.
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "dense_lu.hpp"
#include "integration_run.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen::runtime::detail {
namespace {

using Complex = std::complex<double>;

// The method's constants (Hairer's radau5.f; also scipy's _ivp/radau.py).
const double kS6 = std::sqrt(6.0);
const double kC[3] = {(4.0 - kS6) / 10.0, (4.0 + kS6) / 10.0, 1.0};  // collocation nodes
// The error estimate's combination of the stages, divided by h.
const double kE[3] = {(-13.0 - 7.0 * kS6) / 3.0, (-13.0 + 7.0 * kS6) / 3.0, -1.0 / 3.0};
// The eigenvalues of the inverse of the method's matrix A: mu_r, mu_c and its conjugate.
const double kMuReal = 3.0 + std::cbrt(9.0) - std::cbrt(3.0);
const Complex kMuComplex(3.0 + 0.5 * (std::cbrt(3.0) - std::cbrt(9.0)),
                         -0.5 * (std::pow(3.0, 5.0 / 6.0) + std::pow(3.0, 7.0 / 6.0)));
// Z = T W and W = T^-1 Z, with T^-1 A^-1 T = diag(mu_r, [[a, -b], [b, a]]).
constexpr double kT[3][3] = {{0.09443876248897524, -0.14125529502095421, 0.03002919410514742},
                             {0.25021312296533332, 0.20412935229379994, -0.38294211275726192},
                             {1.0, 1.0, 0.0}};
constexpr double kTI[3][3] = {{4.17871859155190428, 0.32768282076106237, 0.52337644549944951},
                              {-4.17871859155190428, -0.32768282076106237, 0.47662355450055044},
                              {0.50287263494578682, -2.57192694985560522, 0.59603920482822492}};
// The collocation polynomial over a step: x(t + s h) = x + sum_k Q_k s^(k+1), Q = Z^T P.
const double kP[3][3] = {
    {13.0 / 3.0 + 7.0 * kS6 / 3.0, -23.0 / 3.0 - 22.0 * kS6 / 3.0, 10.0 / 3.0 + 5.0 * kS6},
    {13.0 / 3.0 - 7.0 * kS6 / 3.0, -23.0 / 3.0 + 22.0 * kS6 / 3.0, 10.0 / 3.0 - 5.0 * kS6},
    {1.0 / 3.0, -8.0 / 3.0, 10.0 / 3.0}};

constexpr int kMaxNewton = 6;
constexpr double kMinFactor = 0.2, kMaxFactor = 10.0;
constexpr double kJacobianRate = 1e-3;  // Hairer's THET: 0.1 cost Simeon's FE crank twice the steps

class Radau {
 public:
  Radau(Run& run, const Jacobian& jacobian, double* x) : run_(run), jacobian_(jacobian), x_(x), n_(run.n()) {
    const size_t n = static_cast<size_t>(std::max(n_, 1));
    J_.assign(n * n, 0.0);
    lu_real_.assign(n * n, 0.0);
    lu_complex_.assign(n * n, Complex());
    pivots_real_.assign(n, 0);
    pivots_complex_.assign(n, 0);
    for (auto* v : {&Z_, &W_, &F_, &Q_}) v->assign(3 * n, 0.0);
    for (auto* v : {&f_, &y_new_, &stage_, &scale_, &error_, &ze_, &rhs_real_, &x_old_, &out_})
      v->assign(n, 0.0);
    rhs_complex_.assign(n, Complex());
    const double rtol = run.opt().rtol;
    newton_tol_ = rtol > 0 ? std::max(10 * kEps / rtol, std::min(0.03, std::sqrt(rtol))) : 0.03;
  }

  // Returns the time of the state left in x.
  double integrate(double t0) {
    const IntegrationOptions& opt = run_.opt();
    const OutputGrid grid(t0, opt.dt, opt.t_end);
    if (!run_.emit(t0, x_) || grid.intervals() == 0) return t0;
    if (n_ == 0) {
      for (long k = 1; k <= grid.intervals(); ++k)
        if (!run_.emit(grid.time(k), x_)) return grid.time(k - 1);
      return opt.t_end;
    }
    const double h_max = opt.h_max > 0 ? opt.h_max : opt.t_end - t0;
    double t = t0;
    if (!run_.eval(t, x_, f_.data()) || !evaluate_jacobian(t)) return t;
    double h = std::min(opt.h0 > 0 ? opt.h0 : initial_step(t, h_max), h_max);
    long next = 1;
    bool first = true, rejected = false;
    double h_accepted = 0.0, error_accepted = 0.0;  // Gustafsson's memory of the last accepted step
    double t_previous = t0, h_previous = 0.0;       // the last accepted step, whose polynomial predicts
    while (true) {
      StepStats& s = run_.stats();
      if (s.accepted + s.rejected + s.newton_failures >= opt.max_steps) {
        run_.fail(Status::kMaxSteps, max_steps_message(opt), t, x_);
        return t;
      }
      const bool last = t + 1.01 * h >= opt.t_end;
      if (last) h = opt.t_end - t;
      const double h_min = std::max({opt.h_min, 10 * kEps * std::abs(t), 1e-300});
      if (h < h_min) {
        run_.fail(Status::kStepSizeTooSmall, too_small_message(h), t, x_);
        return t;
      }
      if (!(factored_ && h == h_factored_) && !factor(h)) {
        ++s.newton_failures;
        failure_ = Failure::kSingular;
        h *= 0.5;
        continue;
      }
      if (first)
        std::fill(Z_.begin(), Z_.end(), 0.0);
      else
        predict(t_previous, h_previous, t, h);
      int iterations = 0;
      double rate = 0.0;
      if (!newton(t, h, &iterations, &rate)) {
        if (run_.failed()) return t;
        ++s.newton_failures;
        // Hairer's radau5: half the step, a fresh Jacobian if it was not,
        // and no growth after the step that succeeds.
        if (!jacobian_current_) {
          if (!evaluate_jacobian(t)) return t;
          factored_ = false;
        }
        rejected = true;
        h *= 0.5;
        continue;
      }
      const double err = error_norm(t, h, first || rejected);
      if (run_.failed()) return t;
      const double safety = 0.9 * (2 * kMaxNewton + 1) / (2 * kMaxNewton + iterations);
      // Hairer's quot = h / h_new, from the error alone.
      double quot = std::clamp(std::pow(err, 0.25) / safety, 1.0 / kMaxFactor, 1.0 / kMinFactor);
      if (!(err <= 1.0)) {
        ++s.rejected;
        failure_ = Failure::kErrorTest;
        rejected = true;
        h /= std::isfinite(err) ? quot : 1.0 / kMinFactor;
        continue;
      }
      // Accepted.
      ++s.accepted;
      if (!first) {  // Gustafsson's prediction from the last two accepted steps
        const double gustafsson =
            std::clamp(h_accepted / h * std::pow(err * err / error_accepted, 0.25) / safety, 1.0 / kMaxFactor,
                       1.0 / kMinFactor);
        quot = std::max(quot, gustafsson);
      }
      h_accepted = h;
      error_accepted = std::max(1e-2, err);
      const double t_old = t;
      if (!advance(t, h, last, grid, next) || last) return t;
      // The next step: h kept (and the factors with it) when a slow
      // contraction does not call for a new Jacobian and the change would
      // be small; else a new h, factored anew.
      const bool new_jacobian = iterations > 2 && rate > kJacobianRate;
      double h_new = std::min(h / quot, h_max);
      if (rejected) h_new = std::min(h_new, h);
      if (!new_jacobian && h_new >= h && h_new < 1.2 * h) h_new = h;
      if (new_jacobian) {
        if (!evaluate_jacobian(t)) return t;
        factored_ = false;
      } else {
        jacobian_current_ = false;
      }
      t_previous = t_old;
      h_previous = h;
      first = rejected = false;
      h = h_new;
    }
  }

 private:
  // An accepted step: the output rows inside it from the collocation
  // polynomial, then x = the step's end, projected, and f there. False: stop
  // (t is the time of the state in x).
  bool advance(double& t, double h, bool last, const OutputGrid& grid, long& next) {
    const IntegrationOptions& opt = run_.opt();
    const double t_new = last ? opt.t_end : t + h;
    dense_coefficients();
    std::copy(x_, x_ + n_, x_old_.begin());
    for (; next <= grid.intervals() && grid.time(next) < t_new; ++next) {
      dense((grid.time(next) - t) / h);
      if (!run_.emit(grid.time(next), out_.data())) return false;
    }
    std::copy(y_new_.begin(), y_new_.end(), x_);
    t = t_new;
    if (opt.on_step) opt.on_step(t, run_.stats().accepted);
    if (opt.project) ++run_.stats().projections;
    if (!run_.project(t, x_) || !run_.eval(t, x_, f_.data())) return false;
    if (next <= grid.intervals() && grid.time(next) == t) {
      if (!run_.emit(t, x_)) return false;
      ++next;
    }
    return true;
  }

  double tolerance(int i) const {
    const IntegrationOptions& opt = run_.opt();
    return opt.atol_per_component.empty() ? opt.atol : opt.atol_per_component[i];
  }

  static double ratio_squared(double a, double b) { return a == 0 ? 0.0 : (a / b) * (a / b); }

  bool evaluate_jacobian(double t) {
    ++run_.stats().jacobian_evaluations;
    bool ok = false;
    std::string why;
    try {
      ok = jacobian_(t, x_, J_.data()) && all_finite(J_.data(), n_ * n_);
    } catch (const std::exception& e) {
      why = std::string(": it threw (") + e.what() + ")";
    }
    if (!ok) {
      run_.fail(
          Status::kSolverFailed,
          "the Jacobian could not be evaluated" + why + " (a singular mass matrix or a singular position?)",
          t, x_);
      return false;
    }
    jacobian_current_ = true;
    second_order_ = is_second_order();
    return true;
  }

  // The LU factors of mu_r/h I - J and mu_c/h I - J.
  bool factor(double h) {
    ++run_.stats().factorizations;
    const Complex shift_complex = kMuComplex / h;
    factored_ = factor_shifted(kMuReal / h, lu_real_.data(), pivots_real_.data()) &&
                factor_shifted(shift_complex, lu_complex_.data(), pivots_complex_.data());
    h_factored_ = h;
    shift_real_ = kMuReal / h;
    shift_complex_ = shift_complex;
    return factored_;
  }

  // c I - J, factored. For the state equations of a mechanism, q' = u, J is
  // [[0, I], [A, B]] (second_order_), and c I - J reduces to the m x m
  // S = c^2 I - c B - A, 8 times less work than the n x n matrix.
  template <class T>
  bool factor_shifted(T c, T* LU, int* pivots) const {
    const int n = n_, m = n_ / 2;
    if (second_order_) {
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
          LU[i * m + j] = -times(c, T(J_[(m + i) * n + m + j])) - T(J_[(m + i) * n + j]);
      const T c2 = times(c, c);
      for (int i = 0; i < m; ++i) LU[i * m + i] += c2;
      return lu_factor_in_place(LU, m, pivots);
    }
    for (int i = 0; i < n * n; ++i) LU[i] = T(-J_[i]);
    for (int i = 0; i < n; ++i) LU[i * n + i] += c;
    return lu_factor_in_place(LU, n, pivots);
  }

  // b := (c I - J)^-1 b from factor_shifted's factors. Second order: with
  // b = (r1, r2), x2 = S^-1 (c r2 + A r1) and x1 = (r1 + x2) / c.
  template <class T>
  void solve_shifted(T c, const T* LU, const int* pivots, T* b) const {
    const int n = n_, m = n_ / 2;
    if (!second_order_) return lu_solve_in_place(LU, n, pivots, b);
    T* r1 = b;
    T* r2 = b + m;
    for (int i = 0; i < m; ++i) {
      const double* a = &J_[(m + i) * n];
      T v = times(c, r2[i]);
      for (int j = 0; j < m; ++j) v += times(T(a[j]), r1[j]);
      r2[i] = v;
    }
    lu_solve_in_place(LU, m, pivots, r2);
    const T inverse = reciprocal(c);
    for (int i = 0; i < m; ++i) r1[i] = times(r1[i] + r2[i], inverse);
  }

  void solve_real(double* b) const { solve_shifted(shift_real_, lu_real_.data(), pivots_real_.data(), b); }
  void solve_complex(Complex* b) const {
    solve_shifted(shift_complex_, lu_complex_.data(), pivots_complex_.data(), b);
  }

  // Whether J = [[0, I], [A, B]] with n = 2m (exactly, as StateJacobian writes it).
  bool is_second_order() const {
    if (n_ % 2 != 0) return false;
    const int n = n_, m = n_ / 2;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < n; ++j)
        if (J_[i * n + j] != (j == m + i ? 1.0 : 0.0)) return false;
    return true;
  }

  // Simplified Newton for the stages from the prediction in Z; false if it
  // diverges, is too slow, or meets a non-finite derivative.
  bool newton(double t, double h, int* iterations, double* rate) {
    const int n = n_;
    double* Z = Z_.data();
    double* W = W_.data();
    double* F = F_.data();
    for (int i = 0; i < n; ++i) {
      scale_[i] = tolerance(i) + run_.opt().rtol * std::abs(x_[i]);
      for (int r = 0; r < 3; ++r)
        W[r * n + i] = kTI[r][0] * Z[i] + kTI[r][1] * Z[n + i] + kTI[r][2] * Z[2 * n + i];
    }
    const double shift_real = kMuReal / h;
    const Complex shift_complex = kMuComplex / h;
    double norm_old = 0.0;
    *rate = 0.0;
    for (int k = 0; k < kMaxNewton; ++k) {
      *iterations = k + 1;
      ++run_.stats().newton_iterations;
      for (int r = 0; r < 3; ++r) {
        for (int i = 0; i < n; ++i) stage_[i] = x_[i] + Z[r * n + i];
        const int status = run_.eval_recoverable(t + kC[r] * h, stage_.data(), &F[r * n], &non_finite_);
        if (status > 0) failure_ = Failure::kNonFinite;  // a smaller step may help
        if (status != 0) return false;                   // < 0: failed, recorded by the Run
      }
      for (int i = 0; i < n; ++i) {
        const double f0 = F[i], f1 = F[n + i], f2 = F[2 * n + i];
        rhs_real_[i] = kTI[0][0] * f0 + kTI[0][1] * f1 + kTI[0][2] * f2 - shift_real * W[i];
        const Complex w(W[n + i], W[2 * n + i]);
        rhs_complex_[i] = Complex(kTI[1][0] * f0 + kTI[1][1] * f1 + kTI[1][2] * f2,
                                  kTI[2][0] * f0 + kTI[2][1] * f1 + kTI[2][2] * f2) -
                          times(shift_complex, w);
      }
      solve_real(rhs_real_.data());
      solve_complex(rhs_complex_.data());
      double sum = 0.0;
      for (int i = 0; i < n; ++i)
        sum += ratio_squared(rhs_real_[i], scale_[i]) + ratio_squared(rhs_complex_[i].real(), scale_[i]) +
               ratio_squared(rhs_complex_[i].imag(), scale_[i]);
      const double norm = std::sqrt(sum / (3.0 * n));
      if (!std::isfinite(norm)) {
        failure_ = Failure::kDiverged;
        return false;
      }
      if (k > 0) {
        *rate = norm / norm_old;
        // Diverging, or too slow to converge in the iterations left.
        if (*rate >= 1.0 || std::pow(*rate, kMaxNewton - k) / (1.0 - *rate) * norm > newton_tol_) {
          failure_ = *rate >= 1.0 ? Failure::kDiverged : Failure::kSlow;
          last_rate_ = *rate;
          return false;
        }
      }
      for (int i = 0; i < n; ++i) {
        W[i] += rhs_real_[i];
        W[n + i] += rhs_complex_[i].real();
        W[2 * n + i] += rhs_complex_[i].imag();
      }
      for (int i = 0; i < n; ++i)
        for (int r = 0; r < 3; ++r)
          Z[r * n + i] = kT[r][0] * W[i] + kT[r][1] * W[n + i] + kT[r][2] * W[2 * n + i];
      if (norm == 0.0 || (k > 0 && *rate / (1.0 - *rate) * norm < newton_tol_)) {
        for (int i = 0; i < n; ++i) y_new_[i] = x_[i] + Z[2 * n + i];
        return true;
      }
      norm_old = norm;
    }
    failure_ = Failure::kSlow;
    last_rate_ = *rate;
    return false;
  }

  // The RMS of the filtered error estimate (mu_r/h I - J)^-1 (f + E Z / h);
  // after a rejection or on the first step filtered once more through f
  // (Hairer's remedy for the estimate's growth on stiff components).
  double error_norm(double t, double h, bool refine) {
    const int n = n_;
    const double* Z = Z_.data();
    for (int i = 0; i < n; ++i) {
      ze_[i] = (kE[0] * Z[i] + kE[1] * Z[n + i] + kE[2] * Z[2 * n + i]) / h;
      error_[i] = f_[i] + ze_[i];
      scale_[i] = tolerance(i) + run_.opt().rtol * std::max(std::abs(x_[i]), std::abs(y_new_[i]));
    }
    solve_real(error_.data());
    double err = rms(error_.data());
    if (refine && err > 1.0) {
      for (int i = 0; i < n; ++i) stage_[i] = x_[i] + error_[i];
      if (run_.eval_recoverable(t, stage_.data(), error_.data(), &non_finite_) != 0) return 1e10;
      for (int i = 0; i < n; ++i) error_[i] += ze_[i];
      solve_real(error_.data());
      err = rms(error_.data());
    }
    return err;
  }

  double rms(const double* e) const {
    double sum = 0.0;
    for (int i = 0; i < n_; ++i) sum += ratio_squared(e[i], scale_[i]);
    return std::sqrt(sum / n_);
  }

  void dense_coefficients() {
    const int n = n_;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < n; ++i)
        Q_[k * n + i] = Z_[i] * kP[0][k] + Z_[n + i] * kP[1][k] + Z_[2 * n + i] * kP[2][k];
  }

  // The collocation polynomial of the last step at t_old + s h, into out_.
  void dense(double s) {
    const int n = n_;
    for (int i = 0; i < n; ++i) out_[i] = x_old_[i] + s * (Q_[i] + s * (Q_[n + i] + s * Q_[2 * n + i]));
  }

  // Newton's start for a step (t, h): the last accepted step's collocation
  // polynomial, extrapolated to the new nodes, relative to the (projected)
  // state at t.
  void predict(double t_old, double h_old, double t, double h) {
    const int n = n_;
    for (int r = 0; r < 3; ++r) {
      dense((t + kC[r] * h - t_old) / h_old);
      for (int i = 0; i < n; ++i) Z_[r * n + i] = out_[i] - x_[i];
    }
  }

  // Hairer's hinit for an order-3 error estimate.
  double initial_step(double t, double h_max) {
    const double fallback = std::min(1e-6, h_max);
    double dnf = 0, dny = 0;
    for (int i = 0; i < n_; ++i) {
      const double sk = tolerance(i) + run_.opt().rtol * std::abs(x_[i]);
      dnf += ratio_squared(f_[i], sk);
      dny += ratio_squared(x_[i], sk);
    }
    double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
    h = std::min(h, h_max);
    if (!(h > 0 && std::isfinite(h))) return fallback;
    for (int i = 0; i < n_; ++i) stage_[i] = x_[i] + h * f_[i];
    if (!run_.probe(t + h, stage_.data(), error_.data())) return h;
    double der2 = 0;
    for (int i = 0; i < n_; ++i)
      der2 += ratio_squared(error_[i] - f_[i], tolerance(i) + run_.opt().rtol * std::abs(x_[i]));
    const double der12 = std::max(std::sqrt(der2) / h, std::sqrt(dnf));
    const double h1 = der12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / der12, 0.25);
    h = std::min({100 * h, h1, h_max});
    return h > 0 && std::isfinite(h) ? h : fallback;
  }

  // Why the step size ran out, from the last failed attempt.
  std::string too_small_message(double h) const {
    const IntegrationOptions& opt = run_.opt();
    std::string why;
    switch (failure_) {
      case Failure::kNone:
        why = "accepted steps shrank to round-off (a singularity of the solution?)";
        break;
      case Failure::kSingular:
        why = "the iteration matrix I - h J was singular";
        break;
      case Failure::kDiverged:
        why = "Newton's iteration diverged";
        break;
      case Failure::kSlow:
        why = "Newton's iteration converged too slowly (contraction rate " + number(last_rate_) + ")";
        break;
      case Failure::kNonFinite:
        why = non_finite_;
        break;
      case Failure::kErrorTest:
        why = "the error test failed";
        break;
    }
    return "step size " + number(h) + " fell to its minimum: " + why + " (rtol " + number(opt.rtol) +
           ", atol " + number(opt.atol) + ")";
  }

  Run& run_;
  const Jacobian& jacobian_;
  double* x_;
  int n_;
  double newton_tol_ = 0.03;
  bool factored_ = false, jacobian_current_ = false, second_order_ = false;
  double shift_real_ = 0.0;  // mu_r/h and mu_c/h of the factors
  Complex shift_complex_;
  double h_factored_ = 0.0;
  // Why the last attempt failed, for the message if h runs out (no text is built while stepping).
  enum class Failure { kNone, kSingular, kDiverged, kSlow, kNonFinite, kErrorTest } failure_ = Failure::kNone;
  double last_rate_ = 0.0;
  std::string non_finite_;
  std::vector<double> J_, lu_real_;
  std::vector<Complex> lu_complex_, rhs_complex_;
  std::vector<int> pivots_real_, pivots_complex_;
  std::vector<double> Z_, W_, F_, Q_;  // 3 x n: stages, transformed stages, derivatives, dense output
  std::vector<double> f_, y_new_, stage_, scale_, error_, ze_, rhs_real_, x_old_, out_;
};

}  // namespace

IntegrationResult integrate_radau(Run& run, const Jacobian& jacobian, double t0, double* x) {
  Radau radau(run, jacobian, x);
  return run.finish(radau.integrate(t0));
}

}  // namespace kanegen::runtime::detail
