// SPDX-License-Identifier: GPL-2.0-or-later
// The generalized inertia and gravity forces of a flexible body in the
// floating frame of reference, built from its inertia invariants only. This is
// the numeric statement of what the generator forms symbolically, and the
// check that the invariants are complete.
//
// Speeds, all in link-frame components: u = (v0, omega, qdot), v0 the velocity
// of the link origin, omega the link's angular velocity, qdot the elastic
// rates; accelerations (a0, alpha, qddot), a0 the inertial acceleration of the
// origin (a0 = d v0/dt + omega x v0 in link components). A point at
// r_p = r + N q moves with v_p = v0 + omega x r_p + N qdot, so its partial
// velocities are (I, -skew(r_p), N); a rotary inertia J turns with
// omega_p = omega + Nrot qdot. The generalized inertia force is
//   F* = -M(q) (a0, alpha, qddot) + Q(q, qdot, omega).
// Rotary inertias are taken constant in the link frame (their change with the
// small elastic rotation is dropped); their velocity term is the Lagrangian
// one, omega x J omega_p on the rotation equations and nothing on the elastic
// ones, so that the power of F* is exactly -dT/dt.
#pragma once

#include <Eigen/Dense>

#include "fem/invariants.hpp"

namespace kanegen::fem {

/// M(q): (6 + n) x (6 + n), symmetric, rows and columns (v0, omega, qdot):
///   [ m I        -skew(s_p)         S                          ]
///   [  .   I_p(q) + J      int rho skew(r_p) N + J_Nrot        ]
///   [  .          .        int rho N^T N + Nrot^T J Nrot       ]
/// with s_p = s + S q and I_p = int rho (|r_p|^2 I - r_p r_p^T).
Eigen::MatrixXd ffr_mass_matrix(const InertiaInvariants& inv, const Eigen::VectorXd& q);

/// Q(q, qdot, omega): 6 + n, the velocity (centrifugal, Coriolis, gyroscopic) part of F*:
///   -( W^2 s_p + 2 W S qdot,
///      omega x (I_p + J) omega + omega x J_Nrot qdot + 2 int rho r_p x (omega x N qdot),
///      int rho N^T W^2 r_p + 2 sum_c omega_c int rho N^T skew(e_c) N qdot ),   W = skew(omega).
Eigen::VectorXd ffr_velocity_forces(const InertiaInvariants& inv, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& qdot, const Eigen::Vector3d& omega);

/// The generalized force of uniform gravity g (link components): 6 + n, (m g, s_p x g, S^T g).
Eigen::VectorXd ffr_gravity_forces(const InertiaInvariants& inv, const Eigen::VectorXd& q,
                                   const Eigen::Vector3d& g);

/// int rho r_p r_p^T at q: 3 x 3.
Eigen::Matrix3d deformed_second_moment(const InertiaInvariants& inv, const Eigen::VectorXd& q);

}  // namespace kanegen::fem
