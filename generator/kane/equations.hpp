// SPDX-License-Identifier: GPL-2.0-or-later
// Kane's equations F_r + F*_r = 0 of a tree, written as
// M(q) u_dot = f(t, q, u, tau), with the energies, named outputs and the
// recursions, as the named products of a lazy derivation context.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <map>
#include <memory>
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

/// M by world projection on a rigid tree (MassMatrixMethod::world_projection;
/// empty otherwise): M_rs = M_sr = axis[r] . momentum[s] for each pair (r, s),
/// r on s's path, the other entries 0. axis: joint r's partial velocities at
/// the world origin in world axes, (a, o x a) revolute, (0, a) prismatic;
/// momentum: of what moves with u_s = 1, about the world origin (angular,
/// linear). What lets M be emitted as a loop over the pairs.
struct WorldMass {
  std::vector<std::array<GiNaC::ex, 6>> axis, momentum;
  std::vector<std::pair<int, int>> pairs;
};

/// The coordinates and speeds: what they are called, what they move, where
/// they start, how q moves with u. Needs no kinematics.
struct Coordinates {
  std::vector<double> q0, u0;               ///< the initial state
  std::vector<PrescribedSpeed> prescribed;  ///< speeds whose u_dot is given, not solved for
  std::vector<GiNaC::ex> rates;             ///< nq: q_dot as a function of u
  std::vector<std::string> coordinate_names, speed_names, input_names;
  /// Per coordinate: its joint ("" for an elastic coordinate) and the bodies
  /// it moves, in model order: what the run-time message of a mass matrix
  /// that is not positive definite names.
  std::vector<std::string> coordinate_joints;
  std::vector<std::vector<std::string>> moved_bodies;
  /// Per coordinate: 0 free, 1 marked independent (assembly keeps it), 2 prescribed.
  std::vector<int> roles;
};

struct Energies {
  GiNaC::ex kinetic = 0, potential = 0;
  /// The potential energy of gravity alone (its gradient is the gravity kernel's g(q)).
  GiNaC::ex gravity_potential = 0;
  /// The power of every force not from V: dampers (joint, spring, beam),
  /// inputs tau, joint efforts, body-fixed applied forces. 0 for a
  /// conservative model. The drivers of prescribed motions are not in it
  /// (their effort is known only with u_dot: the runtime adds it).
  GiNaC::ex nonconservative_power = 0;
  /// Forces not from V other than the inputs (which simulate leaves at 0),
  /// or prescribed motions: whether simulate --energies has a W_nc column.
  bool nonconservative = false;
};

/// The model's outputs, each expanded into its columns.
struct Outputs {
  std::vector<GiNaC::ex> values;
  std::vector<std::string> names;
  /// Outputs that are constraint forces: (index in values, row of lambda).
  std::vector<std::pair<int, int>> reactions;
};

/// Rigid trees only (both empty with flexible bodies): M u_dot - f for the
/// accelerations Variables::udot, and the generalized gravity g(q) =
/// dV_gravity/dq, both by the recursion of Newton and Euler over the tree
/// (accelerations outward, subtree wrenches inward): O(n), M never formed.
struct InverseDynamics {
  std::vector<GiNaC::ex> inertial, gravity;
};

/// Trees (rigid or flexible) without loops or prescribed motions: u_dot by the
/// articulated-body recursion (kane/articulated_body.hpp), O(n), M never
/// formed; by speed, with the pivots D it divides by and their order.
/// Empty otherwise, and `unavailable` says why.
struct Recursion {
  std::vector<GiNaC::ex> accelerations, pivots;
  std::vector<int> pivot_order;
  std::string unavailable;
  /// Where in the model file the reason lies (a joint's place), or "".
  std::string unavailable_place;
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

/// The products a derivation can give, for DerivationContext::derivations.
enum class Product {
  kinematics,            ///< the tree's rotations, velocities and rest accelerations
  bodies,                ///< each body's inertia and wrench, the bodies' and springs' energies
  mass_matrix,           ///< M, with the bodies' share of f (the same sums over subtrees)
  coordinates,           ///< names, initial state, prescribed speeds, q_dot(u)
  joint_forces,          ///< the joints' springs, dampers, inputs and efforts
  forcing,               ///< f: the bodies' share and the joints' own forces
  energies,              ///< T, V, V of gravity alone, the nonconservative power
  loops,                 ///< the closed loops' constraint rows
  inverse_dynamics,      ///< Newton and Euler's recursion (rigid trees)
  generalized_momentum,  ///< h = M u by the same recursion with velocities (rigid trees)
  recursion,             ///< the articulated-body recursion (open trees)
  outputs,               ///< the outputs' values and names
  count
};

/// Kane's equations and what else the kernels are made of, as named
/// products, each derived on its first request from the products it needs
/// and kept: a kernel asks for what it needs, and what no kernel asks for is
/// never derived. The intermediates go to `program`, which must outlive the
/// context (an expression graph of the program may be made before the
/// products: it reads definitions as it meets them). The model, variables
/// and flexible bodies are kept by reference and must outlive it too.
class DerivationContext {
 public:
  /// A model without flexible bodies' elastic models.
  DerivationContext(const model::Model& model, const symbolic::Variables& vars, symbolic::Program& program,
                    MassMatrixMethod method = MassMatrixMethod::body_frames);
  DerivationContext(const model::Model& model, const symbolic::Variables& vars, symbolic::Program& program,
                    MassMatrixMethod method, const FlexibleBodies& flexible);
  // A temporary would dangle: the context reads the bodies on each request.
  DerivationContext(const model::Model&, const symbolic::Variables&, symbolic::Program&, MassMatrixMethod,
                    FlexibleBodies&&) = delete;
  ~DerivationContext();
  DerivationContext(const DerivationContext&) = delete;
  DerivationContext& operator=(const DerivationContext&) = delete;

  const model::Model& model() const;
  const symbolic::Variables& variables() const;
  int nq() const;
  int nu() const;
  /// The model closes loops (its constraint rows need Product::loops).
  bool has_loops() const;

  const Coordinates& coordinates();
  /// nu*nu, row-major, symmetric.
  const std::vector<GiNaC::ex>& mass_matrix();
  /// Empty unless M was summed by world projection on a rigid tree.
  const WorldMass& world_mass();
  /// nu: gravity, velocity terms, springs, dampers, forces, tau.
  const std::vector<GiNaC::ex>& forcing();
  /// The bodies' share of forcing(): without the joints' own forces.
  const std::vector<GiNaC::ex>& body_forcing();
  const Energies& energies();
  /// Closed loops: M u_dot = f + C^T lambda with C u_dot = gamma.
  const LoopConstraints& loops();
  const InverseDynamics& inverse_dynamics();
  /// Rigid trees only (empty with flexible bodies): the generalized momentum
  /// h = M u by Newton and Euler's recursion with velocities for accelerations, O(n).
  const std::vector<GiNaC::ex>& generalized_momentum();
  const Recursion& recursion();
  const Outputs& outputs();

  /// How many times `product` has been derived: 0 or 1.
  int derivations(Product product) const;

  /// The inputs and the products derived so far (defined in equations.cpp,
  /// whose derivation steps take it).
  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace kanegen::kane
