// SPDX-License-Identifier: GPL-2.0-or-later
// Sparse assembly (issue 39): a body's M and K_e as Eigen::SparseMatrix, from
// triplets, so that memory grows with the mesh and not with its square. The
// entries are those of Body::mass() and Body::stiffness(), summed in the same
// order (elements in order, then point masses).
#pragma once

#include <Eigen/SparseCore>

#include "fem/body.hpp"
#include "fem/boundary.hpp"

namespace kanegen::fem {

/// M: num_dofs x num_dofs, consistent mass including point masses; both triangles stored.
Eigen::SparseMatrix<double> sparse_mass(const Body& body);
/// K_e: num_dofs x num_dofs; both triangles stored.
Eigen::SparseMatrix<double> sparse_stiffness(const Body& body);
/// P^T A P: the rows and columns of the constraint's free dofs.
Eigen::SparseMatrix<double> reduce_sparse(const Constraint& constraint, const Eigen::SparseMatrix<double>& a);

}  // namespace kanegen::fem
