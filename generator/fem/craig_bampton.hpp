// SPDX-License-Identifier: GPL-2.0-or-later
// Craig-Bampton reduction of a body held on some dofs, with interfaces that
// move rigidly (RBE2-like): the constraint modes are the static shapes of
// each rigid motion of one interface (the others and the held dofs at
// zero), then the first k fixed-interface normal modes (every interface dof
// held). Statics at the interfaces are exact in this basis. Every column has
// unit modal mass (psi^T M psi = 1), the constraint modes too: a small
// interface's unit rotation moves little mass, and a coordinate of 1e-6 the
// others' inertia made the loop forces of a solid rod lose 3 digits.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/sparse_modal.hpp"

namespace kanegen::fem {

struct CraigBamptonBasis {
  Eigen::MatrixXd basis;     ///< num_dofs x (constraint modes + k): [Psi, Phi], each of unit modal mass
  int constraint_modes = 0;  ///< 3 per interface in the plane, 6 in space
  Eigen::VectorXd omega;     ///< k: the fixed-interface frequencies (rad/s)
};

/// held: the body's dofs held at zero (a clamped face); interfaces: body
/// nodes of each interface; k fixed-interface modes. Throws
/// std::invalid_argument for an interface that shares held dofs or has too
/// few nodes to move rigidly, or for k above the dofs left. path: as
/// constrained_modes; the sparse path also solves the statics on a sparse
/// LDL^T of K_II (no dense num_dofs x num_dofs matrix).
CraigBamptonBasis craig_bampton(const Body& body, const Constraint& held,
                                const std::vector<std::vector<int>>& interfaces, int k,
                                ModalPath path = ModalPath::kAuto);

}  // namespace kanegen::fem
