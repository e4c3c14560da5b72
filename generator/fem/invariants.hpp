// SPDX-License-Identifier: GPL-2.0-or-later
// Inertia invariants of the floating frame of reference: the integrals that
// the generalized inertia forces of a flexible body reduce to (formulation.md
// section 3), so that the symbolic layer never integrates point by point.
//
// A point of the body is at r + N q in the link frame: r its undeformed
// position, N (3 x n) its displacement shape in link-frame components, q the n
// elastic coordinates (body dofs, reduced dofs or modal amplitudes). Points
// may carry rotary inertia J (cross-section, rigid body on a node) that turns
// with the rotation Nrot q. With N_a the a-th row of N (a, b in x, y, z):
//
//   mass          m        = int rho                       scalar
//   first_moment  s        = int rho r                     3
//   second_moment          = int rho r r^T                 3 x 3
//   S                      = int rho N                     3 x n
//   S_r[3a+b]              = int rho r_a N_b               1 x n each (a 9 x n matrix)
//   S_nn[3a+b]             = int rho N_a^T N_b             n x n each (S_nn[3b+a] = S_nn[3a+b]^T)
//   J                      = sum J_p                       3 x 3
//   J_Nrot                 = sum J_p Nrot_p                3 x n
//   Nrot_J_Nrot            = sum Nrot_p^T J_p Nrot_p       n x n
//
// and, derived from these: int rho skew(r) N (3 x n), int rho N^T N =
// S_nn[0] + S_nn[4] + S_nn[8] (n x n, the consistent mass of the translations),
// the Coriolis matrices int rho N^T skew(e_c) N (n x n, antisymmetric), and
// int rho skew(N_k) N for the q-dependent rotation coupling. floating_frame.hpp
// shows how the mass matrix and the velocity forces are built from them.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "fem/body.hpp"

namespace kanegen::fem {

struct InertiaInvariants {
  int n = 0;
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();
  Eigen::MatrixXd S;                    ///< 3 x n
  Eigen::MatrixXd S_r;                  ///< 9 x n, row 3a+b
  std::array<Eigen::MatrixXd, 9> S_nn;  ///< n x n each, index 3a+b
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  Eigen::MatrixXd J_Nrot;       ///< 3 x n
  Eigen::MatrixXd Nrot_J_Nrot;  ///< n x n

  /// All zero, for n elastic coordinates.
  static InertiaInvariants zero(int n);

  /// int rho skew(r) N: 3 x n.
  Eigen::MatrixXd skew_r_N() const;
  /// int rho N^T N: n x n.
  Eigen::MatrixXd NtN() const;
  /// int rho N^T skew(e_c) N: n x n, antisymmetric (c = 0, 1, 2).
  Eigen::MatrixXd coriolis(int c) const;
  /// The elastic block of the mass matrix, int rho N^T N + Nrot^T J Nrot: n x n.
  Eigen::MatrixXd elastic_mass() const;
};

/// The invariants of a group of mass points, in the group's own dofs (n = dofs.size()).
InertiaInvariants invariants(const MassPointGroup& group);
/// Adds `part` (in the coordinates `dofs` of `into`) to `into`.
void add_scattered(InertiaInvariants& into, const InertiaInvariants& part, const std::vector<int>& dofs);
/// Element e's invariants in its body dofs (element_dofs order), link frame.
InertiaInvariants element_invariants(const Body& body, int e);
/// The body's invariants in all its dofs (elements and point masses).
InertiaInvariants body_invariants(const Body& body);
/// The invariants in new coordinates eta with q = B eta (B: n x m), e.g. the
/// constraint's selection P or the modal basis P Phi.
InertiaInvariants transform(const InertiaInvariants& inv, const Eigen::MatrixXd& B);

}  // namespace kanegen::fem
