// SPDX-License-Identifier: GPL-2.0-or-later
// Shared fixtures of the finite-element tests: a steel beam with different
// bending stiffnesses in its two planes, frequencies of constrained models,
// and the classification of modes by the dofs they move.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "fem/beam_body.hpp"
#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/modal.hpp"

namespace fem_test {

using namespace kanegen::fem;

/// Steel, 20 mm (y) x 10 mm (z) rectangle, so Iz = 4 Iy; J is the
/// Saint-Venant constant of the 2:1 rectangle (0.2287 b h^3).
inline BeamProperties steel_beam(BeamKind kind) {
  BeamProperties p;
  p.kind = kind;
  const double b = 0.02, h = 0.01;
  p.section.A = b * h;
  p.section.Iz = h * b * b * b / 12.0;
  p.section.Iy = b * h * h * h / 12.0;
  p.section.J = 0.2287 * b * h * h * h;
  p.material = Material::isotropic(2.1e11, 0.3, 7850.0);
  return p;
}

/// Euler-Bernoulli cantilever: beta_n L.
inline double cantilever_beta_l(int mode) {
  static const double beta[] = {1.875104068711961, 4.694091132974175, 7.854757438237613};
  return beta[mode];
}

/// omega_n = (beta_n L)^2 sqrt(E I / (rho A L^4)).
inline double bending_omega(double beta_l, double EI, double rho_a, double length) {
  return beta_l * beta_l * std::sqrt(EI / (rho_a * std::pow(length, 4)));
}

/// All frequencies (rad/s) of the constrained model K, M.
inline Eigen::VectorXd frequencies(const Constraint& c, const Eigen::MatrixXd& M, const Eigen::MatrixXd& K) {
  return modal_analysis(c.reduce(M), c.reduce(K)).omega;
}

/// Fraction of a full-dof mode's kinetic energy (phi^T M_sub phi) in the dofs of the given kinds.
inline double energy_fraction(const Body& body, const Eigen::MatrixXd& M, const Eigen::VectorXd& phi,
                              const std::vector<DofKind>& kinds) {
  Eigen::VectorXd part = Eigen::VectorXd::Zero(phi.size());
  for (int node = 0; node < body.num_nodes(); ++node)
    for (DofKind kind : kinds) {
      const int d = body.dof(node, kind);
      if (d >= 0) part[d] = phi[d];
    }
  return part.dot(M * part) / phi.dot(M * phi);
}

/// Frequencies of the modes (ascending) that put more than half their energy in `kinds`.
inline std::vector<double> frequencies_of(const Body& body, const Constraint& c, const Eigen::MatrixXd& M,
                                          const Eigen::MatrixXd& K, const std::vector<DofKind>& kinds) {
  const ModalBasis modes = modal_analysis(c.reduce(M), c.reduce(K));
  const Eigen::MatrixXd full = c.expand(modes.shapes);
  std::vector<double> out;
  for (int i = 0; i < modes.omega.size(); ++i)
    if (energy_fraction(body, M, full.col(i), kinds) > 0.5) out.push_back(modes.omega[i]);
  return out;
}

inline double rel_error(double value, double reference) { return value / reference - 1.0; }

}  // namespace fem_test
