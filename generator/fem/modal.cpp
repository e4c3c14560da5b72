// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/modal.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace kanegen::fem {

namespace {

constexpr double kClusterTolerance = 1e-8;
constexpr double kTieTolerance = 1e-6;
/// Below this ratio of M's Cholesky pivots, modal_analysis turns the pencil around (eigenpairs_with_mass).
constexpr double kNearlySingularMass = 1e-8;

/// Pivot rows of the n x m cluster basis V, independent of V's orthonormal basis.
std::vector<int> cluster_pivots(Eigen::MatrixXd v) {
  std::vector<int> pivots;
  for (int j = 0; j < v.cols(); ++j) {
    const Eigen::VectorXd norms = v.rowwise().norm();
    const double largest = norms.maxCoeff();
    int pivot = 0;
    while (norms[pivot] < (1.0 - kTieTolerance) * largest) ++pivot;
    pivots.push_back(pivot);
    const Eigen::VectorXd x = v.row(pivot).transpose() / norms[pivot];
    v -= (v * x) * x.transpose();  // project the pivot's direction out of the coefficient space
  }
  return pivots;
}

template <typename Mass>
void canonicalize_cluster(const Mass& M, Eigen::Ref<Eigen::MatrixXd> v) {
  const std::vector<int> pivots = cluster_pivots(v);
  // W[pivots, :] = I; then M-orthonormalize in pivot order (keeps W_j = 0 at later pivots).
  Eigen::MatrixXd w = v * v(pivots, Eigen::all).inverse();
  for (int j = 0; j < w.cols(); ++j) {
    for (int i = 0; i < j; ++i) w.col(j) -= w.col(i).dot(M * w.col(j)) * w.col(i);
    w.col(j) /= std::sqrt(w.col(j).dot(M * w.col(j)));
  }
  v = w;
}

template <typename Mass>
void canonicalize(const Mass& M, const Eigen::VectorXd& eigenvalues, Eigen::MatrixXd& shapes) {
  const int k = static_cast<int>(eigenvalues.size());
  if (shapes.cols() != k || shapes.rows() != M.rows())
    throw std::invalid_argument("canonicalize_modes: shapes must be n x k");
  if (k == 0) return;
  // Rigid-body or near-zero eigenvalues are clustered against the spectrum's scale.
  const double floor = 1e-10 * eigenvalues.cwiseAbs().maxCoeff();
  int begin = 0;
  while (begin < k) {
    int end = begin + 1;
    while (end < k && std::abs(eigenvalues[end] - eigenvalues[end - 1]) <=
                          kClusterTolerance * std::max(std::abs(eigenvalues[end]), floor))
      ++end;
    canonicalize_cluster(M, shapes.middleCols(begin, end - begin));
    begin = end;
  }
}

/// The smallest over the largest squared pivot of M's Cholesky factor (a cheap
/// lower bound of 1/cond(M)'s order), 0 where M is not positive definite.
double mass_pivot_ratio(const Eigen::MatrixXd& M) {
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) return 0.0;
  const Eigen::VectorXd pivots = llt.matrixLLT().diagonal().cwiseAbs2();
  return pivots.minCoeff() / pivots.maxCoeff();
}

/// Every eigenpair of K x = lambda M x that has mass, lambda ascending, x
/// M-normalized. The standard reduction factors M, which fails or loses the
/// low modes where M is nearly singular: CalculiX's reduced mass quadrature
/// of the 10-node tetrahedron (4 points) and the wedges (2) gives such an M,
/// singular at rounding, and a Cholesky of it put a free C3D10 bar's rigid
/// modes at 8-53 rad/s. There the pencil is turned around, as a shift-invert
/// Lanczos (CalculiX's) sees it: M x = mu (K + sigma M) x with lambda = 1/mu -
/// sigma, whose right side is positive definite for any K >= 0, and the modes
/// without mass (mu at rounding, lambda beyond 1e12 sigma) are left out.
/// Elsewhere the standard form is kept (the shipped models' modes, and so
/// generated/, unchanged).
void eigenpairs_with_mass(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, Eigen::VectorXd& values,
                          Eigen::MatrixXd& shapes) {
  const int n = static_cast<int>(M.rows());
  if (mass_pivot_ratio(M) >= kNearlySingularMass) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
        K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (solver.info() != Eigen::Success)
      throw std::runtime_error("modal_analysis: the eigensolver failed (is M positive definite?)");
    values = solver.eigenvalues();
    shapes = solver.eigenvectors();
    return;
  }
  const double sigma = 1e-6 * K.trace() / M.trace();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      M, K + sigma * M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success || !(sigma > 0.0))
    throw std::runtime_error(
        "modal_analysis: the eigensolver failed (M is nearly singular and K + sigma M is not positive "
        "definite: is K negative somewhere?)");
  const Eigen::VectorXd& mu = solver.eigenvalues();  // ascending: mu descending is lambda ascending
  int with_mass = 0;
  while (with_mass < n && mu[n - 1 - with_mass] > 1e-12 / sigma) ++with_mass;
  values.resize(with_mass);
  shapes.resize(n, with_mass);
  for (int i = 0; i < with_mass; ++i) {
    values[i] = 1.0 / mu[n - 1 - i] - sigma;
    const Eigen::VectorXd v = solver.eigenvectors().col(n - 1 - i);
    shapes.col(i) = v / std::sqrt(v.dot(M * v));
  }
}

}  // namespace

void canonicalize_modes(const Eigen::MatrixXd& M, const Eigen::VectorXd& eigenvalues,
                        Eigen::MatrixXd& shapes) {
  canonicalize(M, eigenvalues, shapes);
}

void canonicalize_modes(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& eigenvalues,
                        Eigen::MatrixXd& shapes) {
  canonicalize(M, eigenvalues, shapes);
}

ModalBasis modal_analysis(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, int k) {
  const int n = static_cast<int>(M.rows());
  if (M.cols() != n || K.rows() != n || K.cols() != n)
    throw std::invalid_argument("modal_analysis: M and K must be n x n");
  Eigen::VectorXd all_values;
  Eigen::MatrixXd all_shapes;
  eigenpairs_with_mass(M, K, all_values, all_shapes);
  const int with_mass = static_cast<int>(all_values.size());
  if (k < 0 || k > n) k = with_mass;
  if (k > with_mass)
    throw std::runtime_error("modal_analysis: " + std::to_string(k) + " modes asked for, but only " +
                             std::to_string(with_mass) + " of the " + std::to_string(n) +
                             " have mass (the mesh's mass quadrature leaves the others without it); ask for "
                             "fewer modes");
  // Canonicalize over all modes first, so that a cluster cut by k is still whole.
  canonicalize_modes(M, all_values, all_shapes);
  ModalBasis basis;
  basis.eigenvalues = all_values.head(k);
  basis.omega = basis.eigenvalues.cwiseMax(0.0).cwiseSqrt();
  basis.shapes = all_shapes.leftCols(k);
  basis.reduced_mass = basis.shapes.transpose() * M * basis.shapes;
  basis.reduced_stiffness = basis.shapes.transpose() * K * basis.shapes;
  return basis;
}

}  // namespace kanegen::fem
