// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/modal.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace kanegen::fem {

namespace {

constexpr double kClusterTolerance = 1e-8;
constexpr double kTieTolerance = 1e-6;

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
  if (k < 0 || k > n) k = n;
  // EXPERIMENT: M x = mu (K + sigma M) x, lambda = 1/mu - sigma (M may be nearly singular).
  const double sigma = 1e-6 * K.trace() / M.trace();
  const Eigen::MatrixXd B = K + sigma * M;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      M, B, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("modal_analysis: the eigensolver failed (is M positive definite?)");
  Eigen::VectorXd all_values(n);
  Eigen::MatrixXd all_shapes(n, n);
  for (int i = 0; i < n; ++i) {
    const double mu = solver.eigenvalues()[n - 1 - i];
    all_values[i] = 1.0 / mu - sigma;
    const Eigen::VectorXd v = solver.eigenvectors().col(n - 1 - i);
    all_shapes.col(i) = v / std::sqrt(v.dot(M * v));
  }
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
