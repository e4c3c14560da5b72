// SPDX-License-Identifier: MIT
// What every ODE method (rk4.cpp, dopri5.cpp, radau.cpp, cvode.cpp) shares:
// the output grid, and the Run that counts, checks every derivative, calls
// the observer and turns failures into results that name the time and
// state. Private to the runtime library. It sits below the methods and the
// registry (methods.hpp): the types only, nothing that dispatches.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>

#include "kanegen/runtime/integration_types.hpp"

namespace kanegen::runtime::detail {

inline constexpr double kEps = std::numeric_limits<double>::epsilon();

inline std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

inline bool all_finite(const double* x, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) return false;
  }
  return true;
}

// The output times t0, t0 + dt, ..., t_end. Times are computed from the
// index, not accumulated, so they carry no drift; an interval count within
// round-off of an integer is rounded rather than producing a sliver.
class OutputGrid {
 public:
  OutputGrid(double t0, double dt, double t_end) : t0_(t0), dt_(dt), t_end_(t_end) {
    const double r = (t_end - t0) / dt;
    const double nearest = std::round(r);
    const bool integral = std::abs(r - nearest) <= 1e-9 * std::max(1.0, r);
    intervals_ = static_cast<long>(integral ? nearest : std::ceil(r));
    if (t_end > t0) intervals_ = std::max(intervals_, 1L);
  }
  long intervals() const { return intervals_; }
  double time(long k) const { return k >= intervals_ ? t_end_ : t0_ + static_cast<double>(k) * dt_; }

 private:
  double t0_, dt_, t_end_;
  long intervals_ = 0;
};

// State shared by all methods: counts, checks every derivative, calls the
// observer, and turns failures into results that name the time and state.
class Run {
 public:
  Run(const Rhs& rhs, const IntegrationOptions& opt, int n, const Observer& observer)
      : rhs_(rhs), opt_(opt), n_(n), observer_(observer) {}

  const IntegrationOptions& opt() const { return opt_; }
  int n() const { return n_; }
  StepStats& stats() { return result_.stats; }

  // Evaluates the right-hand side; on failure records why and returns false.
  bool eval(double t, const double* x, double* xdot) {
    ++result_.stats.rhs_evals;
    bool ok = false;
    try {
      ok = rhs_(t, x, xdot);
    } catch (const std::exception& e) {
      fail(Status::kRhsFailed, std::string("right-hand side threw (") + e.what() + ")", t, x);
      return false;
    }
    if (!ok) {
      fail(Status::kRhsFailed, "right-hand side failed", t, x);
      return false;
    }
    for (int i = 0; i < n_; ++i) {
      if (!std::isfinite(xdot[i])) {
        fail(Status::kNonFinite, "right-hand side returned d(" + name(i) + ")/dt = " + number(xdot[i]), t, x);
        return false;
      }
    }
    return true;
  }

  // For implicit methods, whose Newton iterates may stray where the
  // derivative is not finite (the step is then retried, smaller): 0 on
  // success, 1 for a non-finite derivative (not recorded; its text in
  // *non_finite), -1 if the right-hand side failed (recorded).
  int eval_recoverable(double t, const double* x, double* xdot, std::string* non_finite) {
    ++result_.stats.rhs_evals;
    bool ok = false;
    try {
      ok = rhs_(t, x, xdot);
    } catch (const std::exception& e) {
      fail(Status::kRhsFailed, std::string("right-hand side threw (") + e.what() + ")", t, x);
      return -1;
    }
    if (!ok) {
      fail(Status::kRhsFailed, "right-hand side failed", t, x);
      return -1;
    }
    for (int i = 0; i < n_; ++i) {
      if (!std::isfinite(xdot[i])) {
        *non_finite =
            "right-hand side returned d(" + name(i) + ")/dt = " + number(xdot[i]) + " at t=" + number(t);
        return 1;
      }
    }
    return 0;
  }

  // Evaluates without recording a failure (for probes off the trajectory).
  bool probe(double t, const double* x, double* xdot) {
    ++result_.stats.rhs_evals;
    try {
      return rhs_(t, x, xdot) && all_finite(xdot, n_);
    } catch (const std::exception&) {
      return false;
    }
  }

  // Applies opt.project to an accepted state; false (and a result) if it fails.
  bool project(double t, double* x) {
    if (!opt_.project) return true;
    std::string why;
    if (opt_.project(t, x, &why)) return true;
    fail(Status::kRhsFailed, "projection onto the constraints failed: " + why, t, x);
    return false;
  }

  // Counts an accepted step ending at t and tells opt.on_step.
  void accepted(double t) {
    ++result_.stats.accepted;
    if (opt_.on_step) opt_.on_step(t, result_.stats.accepted);
  }

  // Calls the observer; false (and a result) if it asks to stop.
  bool emit(double t, const double* x) {
    if (!observer_ || observer_(t, x)) return true;
    result_.status = Status::kStoppedByObserver;
    result_.message = "stopped by the observer at t=" + number(t);
    return false;
  }

  // Records a failure at (t, x) unless one is already recorded.
  void fail(Status status, const std::string& what, double t, const double* x) {
    if (failed()) return;
    result_.status = status;
    result_.message = what + " at t=" + number(t) + ", state " + state(x);
  }
  bool failed() const { return result_.status != Status::kSuccess; }

  // The result, with `t` as the time of the state left in x.
  IntegrationResult finish(double t) {
    result_.t = t;
    return result_;
  }

 private:
  std::string name(int i) const {
    return i < static_cast<int>(opt_.state_names.size()) ? opt_.state_names[i]
                                                         : "x[" + std::to_string(i) + "]";
  }
  std::string state(const double* x) const {
    std::string s = "[";
    for (int i = 0; i < n_; ++i) s += (i ? ", " : "") + name(i) + "=" + number(x[i]);
    return s + "]";
  }

  const Rhs& rhs_;
  const IntegrationOptions& opt_;
  int n_;
  const Observer& observer_;
  IntegrationResult result_;
};

/// "reached max_steps = N before t_end = T".
inline std::string max_steps_message(const IntegrationOptions& opt) {
  return "reached max_steps = " + std::to_string(opt.max_steps) + " before t_end = " + number(opt.t_end);
}

}  // namespace kanegen::runtime::detail
