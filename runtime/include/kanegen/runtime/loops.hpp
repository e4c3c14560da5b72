// SPDX-License-Identifier: MIT
// Closed loops at run time: assembly of a consistent initial state from a
// partial one, and the projection that keeps a simulation on Phi(q) = 0 and
// C(q) u = 0 (Newton steps of least norm, after each accepted step).
#pragma once

#include <string>
#include <vector>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

class Metric;

/// What assembly did, for the user.
struct Assembly {
  std::vector<int> independent;  ///< coordinates held at their given values
  bool picked = false;           ///< chosen by the solver (none was marked in the model)
  int iterations = 0;            ///< Newton iterations on the positions
  double residual = 0.0;         ///< largest |Phi| afterwards
};

class LoopSolver {
 public:
  /// Positions count as closed when every |Phi_i| <= tolerance.
  explicit LoopSolver(const Model& model, double tolerance = 1e-12);

  bool active() const { return nc_ > 0; }
  /// Largest |Phi_i(q)|, and its row in *row if given.
  double residual(const double* q, int* row = nullptr) const;

  /// Closes the loops at t = 0 from a partial state: the coordinates marked
  /// independent in the model (else a set the solver picks, by the columns
  /// of C that leave the best-conditioned rest) and the prescribed ones
  /// keep their values; the others move by Newton. Then the dependent
  /// speeds follow from C u = 0. Throws RunError naming the loop that does
  /// not close and the configuration.
  Assembly assemble(double* q, double* u) const;

  /// Puts (q, u) back on Phi = 0, C u = 0 by least-norm corrections of the
  /// coordinates that are not prescribed. False, with the reason in *why,
  /// if Newton does not converge (a singular or torn configuration).
  bool project(double* q, double* u, std::string* why) const;

  /// "name (role)" of coordinate i, for messages.
  std::string describe(const std::vector<int>& coordinates) const;

 private:
  /// Newton on Phi with only the coordinates in `moving` changing.
  /// The steps are least-norm in `metric` (the mass matrix) if given, else Euclidean.
  bool close_positions(double* q, const std::vector<int>& moving, const Metric* metric, int* iterations,
                       std::string* why) const;
  /// u_moving corrected so that C u = 0.
  bool close_speeds(const double* q, double* u, const std::vector<int>& moving, const Metric* metric,
                    std::string* why) const;
  std::string configuration(const double* q) const;

  const Model& model_;
  int nc_, nq_;
  double tolerance_;
};

}  // namespace kanegen::runtime
