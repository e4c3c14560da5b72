// Kane's equations of a rigid tree evaluated numerically at one state, from
// the position functions (poses.hpp) differentiated by dual numbers:
//   M_rs = sum_i m_i v_r.v_s + w_r.I_i w_s,
//   f_r  = sum_i v_r.m_i (g - a_i) + w_r.(-I_i alpha_i - w_i x I_i w_i)
//          + sum_forces v_r(point).F - k (q_r - rest) - c u_r + tau_r,
// with v_r = d(com)/dq_r, [w_r]x = dR/dq_r R^T, and a_i, alpha_i the
// accelerations at u_dot = 0 (second derivatives along u). Independent of the
// symbolic generator by construction: no GiNaC, no shared code.
#pragma once

#include <vector>

#include "numeric/instance.hpp"

namespace kanegen::numeric {

struct State {
  double t = 0;
  std::vector<double> q, u;
  std::vector<double> tau;  ///< one per coordinate; used for actuated joints only
};

struct Evaluation {
  int n = 0;
  std::vector<double> mass_matrix;  ///< n*n, row-major
  std::vector<double> forcing;      ///< n
  std::vector<double> udot;         ///< n, M udot = f (empty if M is not positive definite)
  double kinetic_energy = 0;
  double potential_energy = 0;       ///< gravity, springs, -F.p of world-frame forces
  double nonconservative_power = 0;  ///< dampers, inputs, body-frame forces
  std::vector<double> outputs;       ///< point outputs as x, y, z; joint outputs one each
};

/// Everything at one state. Throws std::invalid_argument on wrong sizes.
Evaluation evaluate(const Instance& model, const State& state);

/// Only the power of the non-conservative forces (cheaper: one pass along u).
double nonconservative_power(const Instance& model, const State& state);

}  // namespace kanegen::numeric
