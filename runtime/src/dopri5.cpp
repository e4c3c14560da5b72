// SPDX-License-Identifier: MIT
// Dormand-Prince 5(4): adaptive, FSAL, with Hairer's dense output and step
// size controller (DOPRI5), behind the registry's entry (methods.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "integration_run.hpp"
#include "kanegen/runtime/methods.hpp"

namespace kanegen::runtime::detail {
namespace {

// Dormand & Prince (1980) tableau, error coefficients e = b5 - b4 and the
// dense-output coefficients d of Hairer's DOPRI5 (contd5).
constexpr double c2 = 0.2, c3 = 0.3, c4 = 0.8, c5 = 8.0 / 9.0;
constexpr double a21 = 0.2;
constexpr double a31 = 3.0 / 40.0, a32 = 9.0 / 40.0;
constexpr double a41 = 44.0 / 45.0, a42 = -56.0 / 15.0, a43 = 32.0 / 9.0;
constexpr double a51 = 19372.0 / 6561.0, a52 = -25360.0 / 2187.0, a53 = 64448.0 / 6561.0,
                 a54 = -212.0 / 729.0;
constexpr double a61 = 9017.0 / 3168.0, a62 = -355.0 / 33.0, a63 = 46732.0 / 5247.0, a64 = 49.0 / 176.0,
                 a65 = -5103.0 / 18656.0;
constexpr double a71 = 35.0 / 384.0, a73 = 500.0 / 1113.0, a74 = 125.0 / 192.0, a75 = -2187.0 / 6784.0,
                 a76 = 11.0 / 84.0;
constexpr double e1 = 71.0 / 57600.0, e3 = -71.0 / 16695.0, e4 = 71.0 / 1920.0, e5 = -17253.0 / 339200.0,
                 e6 = 22.0 / 525.0, e7 = -1.0 / 40.0;
constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                 d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                 d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;

class Dopri5 {
 public:
  Dopri5(Run& run, double* y) : run_(run), n_(run.n()), y_(y) {
    const size_t m = static_cast<size_t>(std::max(n_, 1));
    for (auto* v : {&k1_, &k2_, &k3_, &k4_, &k5_, &k6_, &k7_, &y1_, &ys_, &out_}) v->assign(m, 0.0);
    cont_.assign(5 * m, 0.0);
  }

  // Returns the time of the state left in y.
  double integrate(double t0) {
    const IntegrationOptions& opt = run_.opt();
    const OutputGrid grid(t0, opt.dt, opt.t_end);
    const double h_max = opt.h_max > 0 ? opt.h_max : std::max(opt.t_end - t0, 0.0);
    double t = t0;
    if (!run_.emit(t, y_)) return t;
    if (grid.intervals() == 0) return t;
    if (!run_.eval(t, y_, k1_.data())) return t;
    double h = std::min(opt.h0 > 0 ? opt.h0 : initial_step(t, h_max), h_max);
    long next = 1;  // index of the next output time
    bool rejected_last = false;
    double fac_old = 1e-4;
    while (true) {
      if (run_.stats().accepted + run_.stats().rejected >= opt.max_steps) {
        run_.fail(Status::kMaxSteps, max_steps_message(opt) + " (stiff problem or too tight a tolerance?)", t,
                  y_);
        return t;
      }
      const bool last = t + 1.01 * h >= opt.t_end;
      if (last) h = opt.t_end - t;
      const double h_min = std::max({opt.h_min, 16 * kEps * std::abs(t), std::numeric_limits<double>::min()});
      if (!last && h < h_min) {
        run_.fail(Status::kStepSizeTooSmall,
                  "step size " + number(h) + " below the minimum " + number(h_min) +
                      ": cannot meet the tolerance (rtol " + number(opt.rtol) + ", atol " + number(opt.atol) +
                      ")",
                  t, y_);
        return t;
      }
      if (!stages(t, h)) return t;
      const double err = error_norm(h);
      // The controller of Hairer's DOPRI5, with optional PI (Lund) stabilisation.
      const double expo = 0.2 - 0.75 * opt.pi_beta;
      const double fac11 = std::pow(err, expo);
      const double fac = std::clamp(fac11 / std::pow(fac_old, opt.pi_beta) / opt.safety, 1.0 / opt.max_factor,
                                    1.0 / opt.min_factor);
      if (!(err <= 1.0)) {  // rejected, also when err is NaN or infinite
        ++run_.stats().rejected;
        const double shrink =
            std::isfinite(err) ? std::min(1.0 / opt.min_factor, fac11 / opt.safety) : 1.0 / opt.min_factor;
        h /= std::max(shrink, 1.0);
        rejected_last = true;
        continue;
      }
      fac_old = std::max(err, 1e-4);
      const double t_new = last ? opt.t_end : t + h;
      run_.accepted(t_new);
      if (next <= grid.intervals() && grid.time(next) < t_new) {
        prepare_dense(h);
        for (; next <= grid.intervals() && grid.time(next) < t_new; ++next) {
          dense((grid.time(next) - t) / h);
          if (!run_.emit(grid.time(next), out_.data())) return t;
        }
      }
      std::copy(y1_.begin(), y1_.begin() + n_, y_);
      k1_.swap(k7_);  // FSAL: f(t_new, y_new) is the next step's first stage
      t = t_new;
      if (opt.project) {  // the projected state has its own first stage
        if (!run_.project(t, y_) || !run_.eval(t, y_, k1_.data())) return t;
      }
      if (next <= grid.intervals() && grid.time(next) == t) {
        if (!run_.emit(t, y_)) return t;
        ++next;
      }
      if (last) return t;
      double h_new = std::min(h / fac, h_max);
      if (rejected_last) h_new = std::min(h_new, h);
      rejected_last = false;
      h = h_new;
    }
  }

 private:
  double sk(int i, double a, double b) const {
    const IntegrationOptions& opt = run_.opt();
    const double atol = opt.atol_per_component.empty() ? opt.atol : opt.atol_per_component[i];
    return atol + opt.rtol * std::max(std::abs(a), std::abs(b));
  }

  // Hairer's hinit: a step with h^5 * max(|f|, |f'|) ~ 0.01 in the error norm.
  // Falls back to a small step when the norms over- or underflow.
  double initial_step(double t, double h_max) {
    const double fallback = std::min(1e-6, h_max);
    double dnf = 0, dny = 0;
    for (int i = 0; i < n_; ++i) {
      dnf += ratio_squared(k1_[i], sk(i, y_[i], 0.0));
      dny += ratio_squared(y_[i], sk(i, y_[i], 0.0));
    }
    double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
    h = std::min(h, h_max);
    if (!(h > 0 && std::isfinite(h))) return fallback;
    for (int i = 0; i < n_; ++i) ys_[i] = y_[i] + h * k1_[i];
    if (!run_.probe(t + h, ys_.data(), k2_.data())) return h;
    double der2 = 0;
    for (int i = 0; i < n_; ++i) der2 += ratio_squared(k2_[i] - k1_[i], sk(i, y_[i], 0.0));
    const double der12 = std::max(std::sqrt(der2) / h, std::sqrt(dnf));
    const double h1 = der12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / der12, 0.2);
    h = std::min({100 * h, h1, h_max});
    return h > 0 && std::isfinite(h) ? h : fallback;
  }

  // (a / b)^2, with 0 for a == 0 so that a zero weight (atol = 0 and a zero
  // component) does not produce NaN.
  static double ratio_squared(double a, double b) { return a == 0 ? 0.0 : (a / b) * (a / b); }

  // The six new stages of one step; y1 = 5th-order solution, k7 = f(t+h, y1).
  bool stages(double t, double h) {
    const double* y = y_;
    auto combine = [&](std::vector<double>& dst, auto&& row) {
      for (int i = 0; i < n_; ++i) dst[i] = y[i] + h * row(i);
    };
    combine(ys_, [&](int i) { return a21 * k1_[i]; });
    if (!run_.eval(t + c2 * h, ys_.data(), k2_.data())) return false;
    combine(ys_, [&](int i) { return a31 * k1_[i] + a32 * k2_[i]; });
    if (!run_.eval(t + c3 * h, ys_.data(), k3_.data())) return false;
    combine(ys_, [&](int i) { return a41 * k1_[i] + a42 * k2_[i] + a43 * k3_[i]; });
    if (!run_.eval(t + c4 * h, ys_.data(), k4_.data())) return false;
    combine(ys_, [&](int i) { return a51 * k1_[i] + a52 * k2_[i] + a53 * k3_[i] + a54 * k4_[i]; });
    if (!run_.eval(t + c5 * h, ys_.data(), k5_.data())) return false;
    combine(ys_,
            [&](int i) { return a61 * k1_[i] + a62 * k2_[i] + a63 * k3_[i] + a64 * k4_[i] + a65 * k5_[i]; });
    if (!run_.eval(t + h, ys_.data(), k6_.data())) return false;
    combine(y1_,
            [&](int i) { return a71 * k1_[i] + a73 * k3_[i] + a74 * k4_[i] + a75 * k5_[i] + a76 * k6_[i]; });
    if (!all_finite(y1_.data(), n_)) {
      run_.fail(Status::kNonFinite, "state overflowed in the step of size " + number(h) + " starting", t, y_);
      return false;
    }
    return run_.eval(t + h, y1_.data(), k7_.data());
  }

  // RMS over components of the embedded error estimate, weighted by
  // atol + rtol * max(|y|, |y1|).
  double error_norm(double h) const {
    if (n_ == 0) return 0.0;
    double sum = 0;
    for (int i = 0; i < n_; ++i) {
      const double e =
          h * (e1 * k1_[i] + e3 * k3_[i] + e4 * k4_[i] + e5 * k5_[i] + e6 * k6_[i] + e7 * k7_[i]);
      sum += ratio_squared(e, sk(i, y_[i], y1_[i]));
    }
    return std::sqrt(sum / n_);
  }

  // Coefficients of the continuous extension over the accepted step.
  void prepare_dense(double h) {
    double* c = cont_.data();
    const size_t n = static_cast<size_t>(n_);
    for (int i = 0; i < n_; ++i) {
      const double ydiff = y1_[i] - y_[i];
      const double bspl = h * k1_[i] - ydiff;
      c[i] = y_[i];
      c[n + i] = ydiff;
      c[2 * n + i] = bspl;
      c[3 * n + i] = ydiff - h * k7_[i] - bspl;
      c[4 * n + i] = h * (d1 * k1_[i] + d3 * k3_[i] + d4 * k4_[i] + d5 * k5_[i] + d6 * k6_[i] + d7 * k7_[i]);
    }
  }

  // State at t + theta * h into out_.
  void dense(double theta) {
    const double* c = cont_.data();
    const size_t n = static_cast<size_t>(n_);
    const double theta1 = 1.0 - theta;
    for (int i = 0; i < n_; ++i) {
      out_[i] = c[i] +
                theta * (c[n + i] + theta1 * (c[2 * n + i] + theta * (c[3 * n + i] + theta1 * c[4 * n + i])));
    }
  }

  Run& run_;
  int n_;
  double* y_;
  std::vector<double> k1_, k2_, k3_, k4_, k5_, k6_, k7_, y1_, ys_, out_, cont_;
};

}  // namespace

IntegrationResult integrate_dopri5(Run& run, const Jacobian&, double t0, double* x) {
  Dopri5 dopri5(run, x);
  return run.finish(dopri5.integrate(t0));
}

}  // namespace kanegen::runtime::detail
