// SPDX-License-Identifier: GPL-2.0-or-later
// Kane's equations F_r + F*_r = 0 of a rigid tree, written as
// M(q) u_dot = f(t, q, u, tau), with the energies and named outputs.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "fem/elastic_model.hpp"
#include "kane/loop_constraints.hpp"
#include "model/model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::kane {

/// A coordinate given as a function of time: its acceleration, piece by
/// piece (the piece holds while t < until; the last for all later times).
struct PrescribedSpeed {
  int speed = -1;
  struct Piece {
    GiNaC::ex acceleration;
    bool has_until = false;
    double until = 0.0;
  };
  std::vector<Piece> pieces;
  GiNaC::ex position0, speed0;  ///< q and q_dot at t = 0, in the parameters
};

struct Equations {
  int nq = 0, nu = 0;
  std::vector<double> q0, u0;               ///< the initial state
  std::vector<PrescribedSpeed> prescribed;  ///< speeds whose u_dot is given, not solved for
  std::vector<GiNaC::ex> mass_matrix;       ///< nu*nu, row-major, symmetric
  /// M by world projection on a rigid tree (MassMatrixMethod::world_projection;
  /// empty otherwise): M_rs = M_sr = axis[r] . momentum[s] for each pair (r, s),
  /// r on s's path, the other entries 0. axis: joint r's partial velocities at
  /// the world origin in world axes, (a, o x a) revolute, (0, a) prismatic;
  /// momentum: of what moves with u_s = 1, about the world origin (angular,
  /// linear). What lets M be emitted as a loop over the pairs.
  struct WorldMass {
    std::vector<std::array<GiNaC::ex, 6>> axis, momentum;
    std::vector<std::pair<int, int>> pairs;
  } world_mass;
  std::vector<GiNaC::ex> forcing;           ///< nu: gravity, velocity terms, springs, dampers, forces, tau
  std::vector<GiNaC::ex> coordinate_rates;  ///< nq: q_dot as a function of u
  GiNaC::ex kinetic_energy, potential_energy;
  /// The power of every force not from V: dampers (joint, spring, beam),
  /// inputs tau, joint efforts, body-fixed applied forces. 0 for a
  /// conservative model. The drivers of prescribed motions are not in it
  /// (their effort is known only with u_dot: the runtime adds it).
  GiNaC::ex nonconservative_power;
  /// Forces not from V other than the inputs (which simulate leaves at 0),
  /// or prescribed motions: whether simulate --energies has a W_nc column.
  bool nonconservative = false;
  std::vector<GiNaC::ex> outputs;
  std::vector<std::string> output_names;
  std::vector<std::string> coordinate_names, speed_names, input_names;
  /// Per coordinate: its joint ("" for an elastic coordinate) and the bodies
  /// it moves, in model order: what the run-time message of a mass matrix
  /// that is not positive definite names.
  std::vector<std::string> coordinate_joints;
  std::vector<std::vector<std::string>> moved_bodies;
  /// Closed loops: M u_dot = f + C^T lambda with C u_dot = gamma.
  LoopConstraints loops;
  /// Per coordinate: 0 free, 1 marked independent (assembly keeps it), 2 prescribed.
  std::vector<int> coordinate_role;
  /// The potential energy of gravity alone (its gradient is the gravity kernel's g(q)).
  GiNaC::ex gravity_potential;
  /// Rigid trees only (empty with flexible bodies): M u_dot - f for the
  /// accelerations Variables::udot, and the generalized gravity g(q) =
  /// dV_gravity/dq, both by the recursion of Newton and Euler over the tree
  /// (accelerations outward, subtree wrenches inward): O(n), M never formed.
  std::vector<GiNaC::ex> inverse_dynamics, gravity_forces;
  /// Rigid trees only (empty with flexible bodies): the generalized momentum
  /// h = M u by the same recursion with velocities for accelerations, O(n).
  std::vector<GiNaC::ex> generalized_momentum;
  /// Trees (rigid or flexible) without loops or prescribed motions: u_dot by the
  /// articulated-body recursion (kane/articulated_body.hpp), O(n), M never
  /// formed; by speed, with the pivots D it divides by and their order.
  /// Empty otherwise, and `recursive_unavailable` says why.
  std::vector<GiNaC::ex> recursive_accelerations, recursive_pivots;
  std::vector<int> recursive_pivot_order;
  std::string recursive_unavailable;
  /// Where in the model file the reason lies (a joint's place), or "".
  std::string recursive_unavailable_place;
  /// Outputs that are constraint forces: (index in outputs, row of lambda).
  std::vector<std::pair<int, int>> reaction_outputs;
};

/// Derives the equations from the partial velocities v_r, w_r of the tree:
///   M_rs = sum_i m_i v_r.v_s + w_r.I_i w_s,
///   f_r  = sum_i v_r.(m_i (g - a_i) + F_i) + w_r.(-I_i alpha_i - w_i x I_i w_i + T_i) + joint terms,
/// (v_r at each centre of mass; a_i, alpha_i the accelerations with u_dot = 0),
/// with the sums over bodies grouped by subtree so that the cost is O(n^2).
/// Two ways to sum M_rs over a subtree: carry the momentum of joint s's
/// subtree up the path frame by frame (cheap for short, sparse trees), or turn
/// it into world axes once and meet each ancestor's world partial velocities
/// (cheap for long chains). Both give the same M; the pipeline keeps the
/// shorter code.
enum class MassMatrixMethod { body_frames, world_projection };

/// The finite-element bodies, by index in Model::bodies.
using FlexibleBodies = std::map<int, fem::ElasticModel>;

Equations derive_equations(const model::Model& model, const symbolic::Variables& vars,
                           symbolic::Program& program,
                           MassMatrixMethod method = MassMatrixMethod::body_frames,
                           const FlexibleBodies& flexible = {});

}  // namespace kanegen::kane
