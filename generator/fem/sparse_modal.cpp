// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/sparse_modal.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fem/sparse_assembly.hpp"

namespace kanegen::fem {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

constexpr double kClusterTolerance = 1e-8;  // as canonicalize_modes clusters
constexpr double kLanczosTolerance = 1e-12;
constexpr int kLanczosIterations = 1000;

/// y = (K - sigma M)^-1 x by a sparse LDL^T: Spectra's operator for the
/// generalized shift-invert mode (SymGEigsShiftSolver calls set_shift).
class ShiftInvertLdlt {
 public:
  using Scalar = double;
  ShiftInvertLdlt(const SparseMatrix& K, const SparseMatrix& M) : K_(K), M_(M) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    ldlt_.compute(K_ - sigma * M_);
    if (ldlt_.info() != Eigen::Success)
      throw std::runtime_error("sparse modal analysis: the factorisation of K - sigma M failed");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<Eigen::VectorXd>(y_out, rows()) = ldlt_.solve(Eigen::Map<const Eigen::VectorXd>(x_in, rows()));
  }

 private:
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
};

/// How many eigenvalues of K phi = lambda M phi lie below s: the negative
/// pivots of K - s M = L D L^T (Sylvester's law of inertia).
int eigenvalues_below(const SparseMatrix& M, const SparseMatrix& K, double s) {
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(K - s * M);
  if (ldlt.info() != Eigen::Success)
    throw std::runtime_error("sparse modal analysis: the factorisation for the Sturm count failed");
  return static_cast<int>((ldlt.vectorD().array() < 0.0).count());
}

/// The negative shift: a millionth of the smallest K_ii / M_ii (an upper
/// bound of the lowest eigenvalue), so that K - sigma M is positive definite
/// with rigid modes at 0 and the lowest modes stay well apart once inverted.
double lanczos_shift(const SparseMatrix& M, const SparseMatrix& K) {
  const Eigen::VectorXd k = K.diagonal(), m = M.diagonal();
  double ratio = -1.0;
  for (Eigen::Index i = 0; i < k.size(); ++i)
    if (m[i] > 0.0 && k[i] > 0.0 && (ratio < 0.0 || k[i] / m[i] < ratio)) ratio = k[i] / m[i];
  if (ratio <= 0.0) throw std::invalid_argument("sparse modal analysis: K or M has no positive diagonal");
  return -1e-6 * ratio;
}

/// n x nev M-orthonormal Lanczos (Ritz) vectors of the nev eigenvalues nearest sigma.
Eigen::MatrixXd lanczos_vectors(const SparseMatrix& M, const SparseMatrix& K, int nev) {
  const int n = static_cast<int>(M.rows());
  const int ncv = std::min(n, std::max(2 * nev + 1, nev + 20));
  ShiftInvertLdlt op(K, M);
  Spectra::SparseSymMatProd<double> bop(M);
  Spectra::SymGEigsShiftSolver<ShiftInvertLdlt, Spectra::SparseSymMatProd<double>,
                               Spectra::GEigsMode::ShiftInvert>
      solver(op, bop, nev, ncv, lanczos_shift(M, K));
  solver.init();  // Spectra's fixed-seed start vector: the same run to run
  solver.compute(Spectra::SortRule::LargestMagn, kLanczosIterations, kLanczosTolerance);
  if (solver.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error("sparse modal analysis: Lanczos did not converge to " + std::to_string(nev) +
                             " modes in " + std::to_string(kLanczosIterations) + " restarts");
  return solver.eigenvectors();
}

bool same_cluster(double a, double b, double floor) {
  return std::abs(b - a) <= kClusterTolerance * std::max(std::abs(b), floor);
}

}  // namespace

ModalBasis sparse_modal_analysis(const SparseMatrix& M, const SparseMatrix& K, int k) {
  const int n = static_cast<int>(M.rows());
  if (M.cols() != n || K.rows() != n || K.cols() != n)
    throw std::invalid_argument("sparse_modal_analysis: M and K must be n x n");
  // Past k, so that k's cluster ends before the last mode computed.
  const int nev = std::min(n - 2, k + std::max(6, k / 2));
  if (k < 1 || k >= nev) throw std::invalid_argument("sparse_modal_analysis: bad mode count");
  // Rayleigh-Ritz on the Lanczos vectors: eigenvalues to the square of their residual.
  const Eigen::MatrixXd V = lanczos_vectors(M, K, nev);
  const Eigen::MatrixXd MV = M * V, KV = K * V;
  const Eigen::MatrixXd Mr = V.transpose() * MV, Kr = V.transpose() * KV;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(
      0.5 * (Kr + Kr.transpose()), 0.5 * (Mr + Mr.transpose()), Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (ritz.info() != Eigen::Success) throw std::runtime_error("sparse modal analysis: Rayleigh-Ritz failed");
  const Eigen::VectorXd values = ritz.eigenvalues();
  // Keep up to the end of k's cluster (c modes), the next one apart.
  const double floor = 1e-10 * values.cwiseAbs().maxCoeff();
  int c = k;
  while (c < nev && same_cluster(values[c - 1], values[c], floor)) ++c;
  if (c == nev)
    throw std::runtime_error("sparse modal analysis: mode " + std::to_string(k) +
                             " repeats past the modes computed; keep fewer modes");
  const double s = 0.5 * (values[c - 1] + values[c]);
  const int below = eigenvalues_below(M, K, s);
  if (below != c)
    throw std::runtime_error("sparse modal analysis: Lanczos found " + std::to_string(c) + " modes below " +
                             std::to_string(s) + " (omega^2), the Sturm count " + std::to_string(below) +
                             " (a repeated frequency missed?); use the dense path");
  Eigen::VectorXd kept = values.head(c);
  Eigen::MatrixXd shapes = V * ritz.eigenvectors().leftCols(c);
  canonicalize_modes(M, kept, shapes);
  ModalBasis basis;
  basis.eigenvalues = kept.head(k);
  basis.omega = basis.eigenvalues.cwiseMax(0.0).cwiseSqrt();
  basis.shapes = shapes.leftCols(k);
  basis.reduced_mass = basis.shapes.transpose() * (M * basis.shapes);
  basis.reduced_stiffness = basis.shapes.transpose() * (K * basis.shapes);
  return basis;
}

ModalBasis constrained_modes(const Body& body, const Constraint& constraint, int k, ModalPath path) {
  if (constraint.num_dofs() != body.num_dofs())
    throw std::invalid_argument("constrained_modes: constraint size");
  // By size, a few modes of a large mesh only: Lanczos wants k well below the dofs.
  const bool sparse = path == ModalPath::kSparse ||
                      (use_sparse_path(constraint.num_free(), path) && 2 * k <= constraint.num_free());
  if (sparse)
    return sparse_modal_analysis(reduce_sparse(constraint, sparse_mass(body)),
                                 reduce_sparse(constraint, sparse_stiffness(body)), k);
  return modal_analysis(constraint.reduce(body.mass()), constraint.reduce(body.stiffness()), k);
}

}  // namespace kanegen::fem
