// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/continuum_foreshortening.hpp"

#include <stdexcept>
#include <string>

#include "fem/continuum_element.hpp"
#include "fem/continuum_prestress.hpp"

namespace kanegen::fem {

namespace {

/// The n x n symmetric matrix of -v, v a row over the pairs: (H)_ij = -v_pair(i, j).
Eigen::MatrixXd negated_pairs(const Eigen::RowVectorXd& v, int n) {
  Eigen::MatrixXd h(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) h(i, j) = -v[pair_index(i, j, n)];
  return h;
}

}  // namespace

Eigen::MatrixXd second_order_fields(const Body& body, const Constraint& held, const Eigen::MatrixXd& basis) {
  if (basis.rows() != body.num_dofs())
    throw std::invalid_argument("second_order_fields: the basis must have num_dofs rows");
  const int n = static_cast<int>(basis.cols());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(body.num_dofs(), pair_count(n));
  for (int e = 0; e < body.num_elements(); ++e) {
    const ContinuumElement& element = continuum_element(body, e);
    const ElementPlacement& placed = body.element(e);
    const Eigen::MatrixXd u_e = placed.T * basis(placed.dofs, Eigen::all);
    g(placed.dofs, Eigen::all) += placed.T.transpose() * element.quadratic_strain_forces(u_e);
  }
  return -static_displacements(body, held, g);
}

Foreshortening continuum_foreshortening(const Body& body, const Eigen::MatrixXd& d, int n,
                                        const std::vector<Eigen::MatrixXd>& points) {
  if (d.rows() != body.num_dofs() || d.cols() != pair_count(n))
    throw std::invalid_argument("continuum_foreshortening: expected " + std::to_string(body.num_dofs()) +
                                " x " + std::to_string(pair_count(n)) + " fields");
  Foreshortening f;
  for (const Eigen::MatrixXd& point : points) {
    const Eigen::MatrixXd at = point * d;  // 3 x pairs
    f.node.push_back({negated_pairs(at.row(0), n), negated_pairs(at.row(1), n), negated_pairs(at.row(2), n)});
  }
  // sum_p m_p (N_p d)_a and sum_p m_p r_b (N_p d)_a over the mass points.
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(3, pair_count(n)),
                  moment = Eigen::MatrixXd::Zero(9, pair_count(n));
  for (const MassPointGroup& group : body.mass_point_groups()) {
    const Eigen::MatrixXd local = d(group.dofs, Eigen::all);
    for (const MassPoint& p : group.points) {
      const Eigen::MatrixXd at = p.mass * (p.N * local);
      mass += at;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) moment.row(3 * a + b) += p.r[b] * at.row(a);
    }
  }
  for (int a = 0; a < 3; ++a) f.mass[a] = negated_pairs(mass.row(a), n);
  for (int ab = 0; ab < 9; ++ab) f.moment[ab] = negated_pairs(moment.row(ab), n);
  return f;
}

void add_second_order_mass(const Body& body, const Eigen::MatrixXd& basis, const Eigen::MatrixXd& d,
                           Foreshortening& f) {
  const auto n = basis.cols();
  if (basis.rows() != body.num_dofs() || d.rows() != body.num_dofs() ||
      d.cols() != pair_count(static_cast<int>(n)))
    throw std::invalid_argument("add_second_order_mass: the basis and fields must have num_dofs rows");
  f.mode_pair = Eigen::MatrixXd::Zero(n, d.cols());
  f.pair_pair = Eigen::MatrixXd::Zero(d.cols(), d.cols());
  for (const MassPointGroup& group : body.mass_point_groups()) {
    const Eigen::MatrixXd modes = basis(group.dofs, Eigen::all), fields = d(group.dofs, Eigen::all);
    for (const MassPoint& p : group.points) {
      const Eigen::MatrixXd first = p.N * modes, second = p.N * fields;  // 3 x n, 3 x pairs
      f.mode_pair.noalias() += p.mass * first.transpose() * second;
      f.pair_pair.noalias() += p.mass * second.transpose() * second;
    }
  }
}

}  // namespace kanegen::fem
