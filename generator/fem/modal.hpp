// SPDX-License-Identifier: GPL-2.0-or-later
// Modal reduction: the generalized eigenproblem K phi = omega^2 M phi of a
// constrained model, mass-normalised modes with a deterministic orientation,
// so that generated code is the same from run to run and machine to machine.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace kanegen::fem {

struct ModalBasis {
  Eigen::VectorXd eigenvalues;        ///< k: omega^2, ascending (negative if a prestress buckles the model)
  Eigen::VectorXd omega;              ///< k: rad/s, sqrt(max(eigenvalue, 0))
  Eigen::MatrixXd shapes;             ///< n x k: Phi, Phi^T M Phi = I
  Eigen::MatrixXd reduced_mass;       ///< k x k: Phi^T M Phi (identity to rounding)
  Eigen::MatrixXd reduced_stiffness;  ///< k x k: Phi^T K Phi (diag(eigenvalues) to rounding)
};

/// The first k modes (k < 0: all that have mass) of K phi = lambda M phi, M:
/// n x n symmetric positive semi-definite (a reduced mass quadrature leaves M
/// singular: its massless modes are not modes), K: n x n symmetric.
/// Orientation: see canonicalize_modes.
ModalBasis modal_analysis(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, int k = -1);

/// Makes M-orthonormal modes unique. Modes whose eigenvalues agree to a relative
/// 1e-8 form one cluster (a single mode is a cluster of one). For each cluster,
/// pivot dofs are picked greedily: the dof whose row of the cluster's shapes has
/// the largest norm (ties within a relative 1e-6 go to the lowest index), then
/// that direction is projected out and the next pivot picked the same way; these
/// choices do not depend on the basis the eigensolver returned. The cluster is
/// then rewritten as the M-orthonormal basis, in pivot order, in which mode j
/// vanishes at the pivots after j and is positive at pivot j. For a single mode
/// this is: largest-magnitude component positive.
void canonicalize_modes(const Eigen::MatrixXd& M, const Eigen::VectorXd& eigenvalues,
                        Eigen::MatrixXd& shapes);
/// The same with a sparse M (fem/sparse_modal.hpp).
void canonicalize_modes(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& eigenvalues,
                        Eigen::MatrixXd& shapes);

}  // namespace kanegen::fem
