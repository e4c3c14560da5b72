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

  /// Puts (q, u) back on Phi = 0, C u = 0 by the mass-orthogonal projection
  /// of the augmented Lagrangian method, moving the coordinates that are not
  /// prescribed (it stays on the branch through singular positions). False,
  /// with the reason in *why, if |Phi| stays above 1e-10 (the loop equations
  /// dependent at a true bifurcation, or a torn configuration).
  bool project(double* q, double* u, std::string* why) const;

  /// udot and lambda of M udot = f + C^T lambda, C udot = gamma: the
  /// generated saddle-point solve, and where it finds the loop equations
  /// (nearly) dependent (a singular position: links in line), the
  /// augmented Lagrangian iteration (Bayo and Ledesma 1996), whose
  /// acceleration is the one of least kinetic-energy norm that the
  /// constraints allow (Gauss's principle), so that the motion passes
  /// through on its physical branch with bounded loop forces. Returns as
  /// Model::constrained_dynamics: 0, k > 0 for a singular M, -k if the
  /// fallback cannot be used either (a prescribed coordinate).
  int dynamics(double t, const double* q, const double* u, const double* tau, double* udot,
               double* lambda) const;

  /// "name (role)" of coordinate i, for messages.
  std::string describe(const std::vector<int>& coordinates) const;

 private:
  /// Newton on Phi with only the coordinates in `moving` changing, by
  /// Euclidean least-norm steps (assembly: far from closed, any branch near the guess).
  bool close_positions(double* q, const std::vector<int>& moving, int* iterations, std::string* why) const;
  /// u_moving corrected so that C u = 0.
  bool close_speeds(const double* q, double* u, const std::vector<int>& moving, std::string* why) const;
  std::string configuration(const double* q) const;
  /// dynamics() where the generated solve gave up: the multipliers with each
  /// loop equation scaled to its own size; false if some are (nearly) dependent.
  bool scaled_dynamics(double t, const double* q, const double* u, const double* tau, const Metric& metric,
                       double* udot, double* lambda) const;
  /// dynamics() at a singular position: the augmented Lagrangian iteration.
  bool augmented_dynamics(double t, const double* q, const double* u, const double* tau, double* udot,
                          double* lambda) const;

  const Model& model_;
  int nc_, nq_;
  double tolerance_;
};

}  // namespace kanegen::runtime
