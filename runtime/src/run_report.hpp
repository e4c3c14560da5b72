// SPDX-License-Identifier: MIT
// What `simulate` adds around the integration for a person watching or
// reading the run (private to the runtime): the energy columns
// (--energies), a progress line on a terminal, and the summary of --stats.
// Kept apart from driver.cpp, which only calls these hooks.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

/// kinetic_energy, potential_energy and total_energy at each row, from the
/// model's own kernels, and nonconservative_work W_nc for a model with
/// forces not from V; also tracks T + V - W_nc for the summary.
class EnergyColumns {
 public:
  EnergyColumns(const Model& model, bool enabled)
      : model_(model), enabled_(enabled), with_work_(enabled && model.info().nonconservative) {}
  /// The column names, appended to `header` if enabled.
  void add_header(std::vector<std::string>& header) const;
  int count() const { return enabled_ ? (with_work_ ? 4 : 3) : 0; }
  /// Whether there is a nonconservative_work column.
  bool with_work() const { return with_work_; }
  /// Whether the model has forces not from V (its T + V need not stay).
  bool nonconservative() const { return model_.info().nonconservative; }
  /// Writes count() values to `out` (if enabled) and records T + V - work
  /// (work: W_nc up to this row, 0 without the column).
  void fill(const double* q, const double* u, double work, double* out);
  /// Largest |(T + V - W_nc)(t) - (T + V)(0)| over the rows, and (T + V)(0).
  double largest_change() const { return largest_change_; }
  double initial() const { return initial_; }
  /// Largest T + |V| over the rows: the size of the energy, for a relative change.
  double scale() const { return scale_; }

 private:
  const Model& model_;
  bool enabled_, with_work_;
  bool first_ = true;
  double initial_ = 0.0, largest_change_ = 0.0, scale_ = 0.0;
};

/// One updating line on stderr ("t = 1.2 of 10 s, wall 3.1 s, 5123 steps"),
/// shown only when stderr is a terminal and the run has lasted more than a
/// second; erased at the end. A pipe or a file gets nothing. The steps are
/// the integrator's accepted steps (on_step, which every integrator calls);
/// before the first step ends, the right-hand sides are counted instead.
class Progress {
 public:
  Progress(std::FILE* err, double t_end);
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  /// Called after every accepted step.
  void on_step(double t, long steps);
  /// Called at every right-hand side; looks at the clock every 64th call.
  void on_rhs(double t);
  /// Erases the line (if one was shown).
  void finish();

 private:
  void update(double t);

  std::FILE* err_;
  double t_end_;
  bool terminal_;
  bool shown_ = false;
  long rhs_evals_ = 0, steps_ = 0;
  std::chrono::steady_clock::time_point start_, last_;
  double quiet_for_ = 1.0;  ///< seconds without a line
};

/// The --stats summary line after the run.
std::string run_summary(long steps, double t_final, const EnergyColumns& energy, bool loops,
                        double largest_loop_residual);

}  // namespace kanegen::runtime
