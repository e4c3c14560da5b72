// SPDX-License-Identifier: GPL-2.0-or-later
// Forward dynamics of a tree in O(n): Kane's M u_dot = f solved by the
// articulated-body recursion (Featherstone's ABA) over the tree's own
// inertias and applied-plus-inertia wrenches, without forming M. A flexible
// body's elastic speeds are a block of the recursion beside its joint's.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "kinematics/tree_kinematics.hpp"
#include "symbolic/program.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

/// One body of the tree (TreeKinematics::bodies order), about its origin in
/// its axes: mass m, first moment h = m c, second moment K, and the wrench
/// (moment about the origin, force) of its applied and rest-acceleration
/// inertia forces, the forcing's share of the body.
struct TreeBody {
  GiNaC::ex mass;
  symbolic::Vec3 moment;
  symbolic::Mat3 second;
  symbolic::Vec3 wrench_moment, wrench_force;
  /// Of that wrench, the applied part alone (point forces off nodes,
  /// springs), body axes: a rigid body's inertia wrench is formed in its
  /// working axes instead (kane/working_motion.*); a flexible body takes
  /// the whole wrench above.
  symbolic::Vec3 applied_moment = symbolic::zero_vec(), applied_force = symbolic::zero_vec();
  /// A flexible body's m elastic speeds, from speed `elastic_first` on
  /// (m = 0, -1 for a rigid body), with its own floating-frame terms: per
  /// speed k, the momentum (angular about the origin, linear) of the body
  /// moving with eta_dot_k = 1 alone; the m x m elastic mass (row-major); the
  /// elastic forcing (stiffness, damping, rest-acceleration inertia, loads).
  int elastic_first = -1;
  std::vector<symbolic::Vec3> elastic_angular, elastic_linear;
  std::vector<GiNaC::ex> elastic_mass, elastic_forcing;
};

struct RecursiveDynamics {
  std::vector<GiNaC::ex> accelerations;  ///< u_dot, by speed
  /// By speed: the articulated inertia D of the joint's subtree about (along)
  /// its axis (a pivot of the body's LDL^T for a flexible body); u_dot is
  /// divided by it, so it must be positive.
  std::vector<GiNaC::ex> pivots;
  /// The speeds in the order their pivots are formed (leaves first).
  std::vector<int> pivot_order;
  /// A speed whose pivot is 0 for every state (its subtree has no inertia
  /// about or along its axis), or -1: then the recursion cannot solve the
  /// tree and the other fields are empty.
  int zero_pivot = -1;
};

/// `joint_forces`: per speed, the joint's own generalized force (spring,
/// damper, input, efforts), the part of f not from the bodies; `speeds`: u.
/// The
/// recursion, with the accelerations that u_dot alone gives (the rest
/// accelerations are in the wrenches):
///   inward:  I^A_i = I_i + sum_c X_c^T (I^A_c - U_c U_c^T / D_c) X_c,
///            p^A_i = -w_i + sum_c X_c^T (p^A_c + U_c (Q_c - S_c^T p^A_c) / D_c),
///            U = I^A S, D = S^T U;
///   outward: a_i = X_i a_p, u_dot = (Q - S^T p^A - U^T a_i) / D, a_i += S u_dot.
/// A flexible body's inertia is (6+m) x (6+m) over [frame motion; eta_ddot]
/// and S = blockdiag(S_joint, 1_m): D is (1+m) x (1+m), factored by an
/// unrolled LDL^T with the elastic speeds first (their block is constant
/// unless something hangs on a node), and the top 6 x 6 of I^A - U D^-1 U^T
/// passes to the parent. A child on a node moves with X_c a_p + Phi eta_ddot
/// (Phi: BodyState::node_partial_*), so its share reaches the parent's
/// elastic rows through Phi. Every intermediate is named in `program`.
RecursiveDynamics articulated_body_dynamics(const kinematics::TreeKinematics& tree,
                                            const std::vector<TreeBody>& bodies,
                                            const std::vector<GiNaC::ex>& joint_forces,
                                            const std::vector<GiNaC::ex>& speeds, symbolic::Program& program);

}  // namespace kanegen::kane
