// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/sparse_assembly.hpp"

#include <stdexcept>
#include <vector>

namespace kanegen::fem {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

/// Appends the dofs x dofs block a.
void add_block(const std::vector<int>& dofs, const Eigen::MatrixXd& a, Triplets& out) {
  for (std::size_t j = 0; j < dofs.size(); ++j)
    for (std::size_t i = 0; i < dofs.size(); ++i)
      out.emplace_back(dofs[i], dofs[j], a(static_cast<int>(i), static_cast<int>(j)));
}

/// T^T A T of element e at its body dofs, as Body::scatter places it.
void add_element(const Body& body, int e, const Eigen::MatrixXd& element_matrix, Triplets& out) {
  const ElementPlacement& placed = body.element(e);
  add_block(placed.dofs, placed.T.transpose() * element_matrix * placed.T, out);
}

Eigen::SparseMatrix<double> from_triplets(int n, const Triplets& triplets) {
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());  // duplicates summed in insertion order
  return a;
}

}  // namespace

Eigen::SparseMatrix<double> sparse_mass(const Body& body) {
  if (body.has_imported_matrices()) return body.imported_mass();
  Triplets triplets;
  for (int e = 0; e < body.num_elements(); ++e)
    add_element(body, e, body.element(e).element->mass(), triplets);
  // The point masses: the groups after the elements' (Body::mass_point_groups), one point each,
  // m N^T N + Nrot^T J Nrot on the node's dofs, as Body::mass adds them.
  const std::vector<MassPointGroup> groups = body.mass_point_groups();
  for (std::size_t g = static_cast<std::size_t>(body.num_elements()); g < groups.size(); ++g)
    for (const MassPoint& p : groups[g].points)
      add_block(groups[g].dofs, p.mass * p.N.transpose() * p.N + p.Nrot.transpose() * p.J * p.Nrot, triplets);
  return from_triplets(body.num_dofs(), triplets);
}

Eigen::SparseMatrix<double> sparse_stiffness(const Body& body) {
  if (body.has_imported_matrices()) return body.imported_stiffness();
  Triplets triplets;
  for (int e = 0; e < body.num_elements(); ++e)
    add_element(body, e, body.element(e).element->stiffness(), triplets);
  return from_triplets(body.num_dofs(), triplets);
}

Eigen::SparseMatrix<double> reduce_sparse(const Constraint& constraint,
                                          const Eigen::SparseMatrix<double>& a) {
  if (a.rows() != constraint.num_dofs() || a.cols() != constraint.num_dofs())
    throw std::invalid_argument("reduce_sparse: the matrix is not num_dofs x num_dofs");
  Triplets triplets;
  triplets.reserve(static_cast<std::size_t>(a.nonZeros()));
  for (int j = 0; j < a.outerSize(); ++j) {
    const int rj = constraint.reduced_index(j);
    if (rj < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it) {
      const int ri = constraint.reduced_index(static_cast<int>(it.row()));
      if (ri >= 0) triplets.emplace_back(ri, rj, it.value());
    }
  }
  return from_triplets(constraint.num_free(), triplets);
}

}  // namespace kanegen::fem
