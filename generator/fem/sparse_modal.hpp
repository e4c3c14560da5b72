// SPDX-License-Identifier: GPL-2.0-or-later
// Modal reduction of large meshes (issue 39): the first modes of
// K phi = lambda M phi by shift-invert Lanczos (Spectra's
// SymGEigsShiftSolver) on a sparse LDL^T factorisation of K - sigma M
// (Eigen's SimplicialLDLT), refined by a Rayleigh-Ritz step on the Lanczos
// vectors, checked by a Sturm count (the inertia of K - s M above the last
// mode kept) and oriented by canonicalize_modes as the dense path orients.
// Time and memory grow with the factor's fill, not with the cube and square
// of the mesh. Below kSparseModalThreshold free dofs the reductions keep the
// dense path, whose results the shipped models' generated code was made from.
#pragma once

#include <Eigen/SparseCore>

#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/modal.hpp"

namespace kanegen::fem {

/// Above this many dofs (free dofs for the eigenproblem, body dofs for the
/// projections) the reductions use the sparse path.
constexpr int kSparseModalThreshold = 1500;

/// Which eigensolver: by size (kAuto), or forced (tests, benchmarks).
enum class ModalPath { kAuto, kDense, kSparse };

/// Whether a problem of n dofs takes the sparse path.
inline bool use_sparse_path(int n, ModalPath path) {
  return path == ModalPath::kSparse || (path == ModalPath::kAuto && n > kSparseModalThreshold);
}

/// The first k (1 <= k < n - 1) modes of K phi = lambda M phi, M symmetric
/// positive definite, K symmetric positive semi-definite (rigid modes at 0
/// are found: the shift is negative). Both triangles stored. The result is as
/// modal_analysis's: ascending, M-orthonormal, canonical orientation (over
/// the modes computed, which extend past k to the end of k's cluster).
/// Throws std::runtime_error if Lanczos does not converge, if the factor
/// fails, or if the Sturm count shows a missed mode.
ModalBasis sparse_modal_analysis(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                                 int k);

/// The first k modes of the body under the constraint (reduced dofs), by
/// modal_analysis on the dense matrices or by sparse_modal_analysis.
ModalBasis constrained_modes(const Body& body, const Constraint& constraint, int k,
                             ModalPath path = ModalPath::kAuto);

}  // namespace kanegen::fem
