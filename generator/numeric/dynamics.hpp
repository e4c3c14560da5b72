// SPDX-License-Identifier: GPL-2.0-or-later
// Kane's equations of a tree of rigid and flexible bodies evaluated
// numerically at one state, from the position functions (poses.hpp, beam.hpp)
// differentiated by dual numbers. The bodies are sums of mass elements: a
// point mass m at world position x(q) with a rotary inertia J (about the
// point, constant in its link's axes) turning with the link and with a small
// elastic rotation theta(q) (link frame): a rigid body is one (m at its
// centre of mass, J its central inertia, theta = 0); a beam is one per Gauss
// point (rho A dx, the section's rho diag(Ip, Iy, Iz) dx turning with the
// torsion) and its tip mass one more (turning with the tip node). Then
//   M_rs = sum m v_r.v_s + W_r.I W_s,
//   f_r  = sum v_r.m (g - a) - W_r.I alpha - w_r.(omega x I Omega)
//          + sum_forces v_r(point).F - k (q_r - rest) - c u_r + tau_r + effort_r(t)
//          - sum_springs (k (l - l0) + c l_dot) dl/dq_r
//          - dU/deta_r - (C eta_dot)_r,
// with v_r = dx/dq_r, w_r = vee(dR/dq_r R^T) the link's partial angular
// velocity, W_r = w_r + R dtheta/dq_r, Omega = omega + R theta_dot, I = R J R^T,
// a, alpha the accelerations at u_dot = 0 (second derivatives along u): for a
// rigid body this is Newton-Euler, for the rotary inertia of the beams it is
// Lagrange's equations of T = 1/2 Omega.I Omega with J fixed in the link.
// A spring enters through the gradient of its length l(q) (its force is
// -(...) times the unit vector along it, and v_r.unit = dl/dq_r), with l_dot
// the derivative of l along u. U is the beam's strain energy (with the
// nonlinear axial strain of geometric stiffening in nodal coordinates), C
// Rayleigh or modal damping. Geometric stiffening in modes moves the beam's
// points by its foreshortening instead (beam.hpp), and its own mass elements
// enter the sums to the generator's order (dynamics.cpp, truncation_samples). Independent of the symbolic
// generator by construction: no GiNaC, no shared code (the basis of the elastic coordinates aside, see
// instance.hpp).
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
  /// n: the sum of the magnitudes of the terms summed into each f_r (|v_r||F|
  /// for a term v_r.F): the scale of its round-off, however the terms are
  /// grouped (in modal coordinates a row's terms can be far larger than the
  /// row; a centripetal force is normal to the partial velocity).
  std::vector<double> forcing_magnitude;
  /// n: udot_p = the prescribed acceleration of each prescribed speed p, the
  /// others from M_ff udot_f = f_f - M_fp udot_p (empty if M_ff is not positive definite).
  std::vector<double> udot;
  std::vector<int> prescribed;                  ///< the prescribed speeds
  std::vector<double> prescribed_acceleration;  ///< their accelerations at t
  double kinetic_energy = 0;
  /// gravity, springs (of joints and between points), strain energy, -F.p of world-frame forces
  double potential_energy = 0;
  /// dampers (joints, springs and beams), inputs, joint efforts, body-frame forces, geometric
  /// stiffness, and the constraint forces of the prescribed speeds with this udot.
  double nonconservative_power = 0;
  /// n: the generalized gravity forces g = dV_gravity/dq = -sum m g.v_r (the
  /// sign of M udot + C u + g = tau), from the same mass elements as f.
  std::vector<double> gravity;
  std::vector<double> gravity_magnitude;  ///< n: sum |v_r| m |g|, the scale of its round-off
  std::vector<double> outputs;            ///< one per column of Instance::output_columns
  // Closed loops (empty for a tree; numeric/loops.hpp). udot is then the
  // solution of M udot = f + C^T lambda, C udot = gamma (empty if S = C M^-1
  // C^T is not positive definite), and nonconservative_power includes
  // loop_power.
  std::vector<double> phi;                  ///< nc
  std::vector<double> constraint_jacobian;  ///< nc * n, row-major
  std::vector<double> constraint_bias;      ///< nc: gamma
  std::vector<double> lambda;               ///< nc, with this udot
  /// The power of the loop forces on the speeds that are solved for,
  /// sum_r (C^T lambda)_r u_r over the free r (the prescribed speeds' rows
  /// are in their constraint forces' power); zero where C u = 0.
  double loop_power = 0;
};

/// Everything at one state. Throws std::invalid_argument on wrong sizes.
Evaluation evaluate(const Instance& model, const State& state);

/// The power of the applied non-conservative forces alone: joint dampers,
/// inputs (actuated joints), joint efforts, the beams' damping, body-frame
/// point forces and the dampers of springs; not the constraint forces of
/// prescribed speeds or loops (what the generated nonconservative_power
/// kernel computes).
double applied_power(const Instance& model, const State& state);

/// Only the power of the non-conservative forces. `udot`: the accelerations
/// the prescribed speeds' constraint forces are taken with ((M udot - f)_p
/// u_p); null: the numeric udot. With loops, plus the loop forces' power
/// (Evaluation::loop_power, with the numeric lambda). Cheaper than evaluate for rigid models
/// without prescribed speeds (one pass along u).
double nonconservative_power(const Instance& model, const State& state,
                             const std::vector<double>* udot = nullptr);

}  // namespace kanegen::numeric
