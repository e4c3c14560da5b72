// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/foreshortening.hpp"

#include <stdexcept>

#include "fem/beam_element.hpp"
#include "fem/quadrature.hpp"

namespace kanegen::fem {
namespace {

using Triple = std::array<Eigen::MatrixXd, 3>;

/// int_0^(xi L) G^T G dx over an element, G its slope rows in eta (rows x n):
/// G is quadratic in x, so 3 Gauss points are exact.
Eigen::MatrixXd slope_integral(const BeamElement& element, const Eigen::MatrixXd& to_eta, double xi) {
  static const QuadratureRule rule = gauss_legendre(3);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(to_eta.cols(), to_eta.cols());
  if (xi <= 0.0) return h;
  for (std::size_t g = 0; g < rule.points.size(); ++g) {
    const Eigen::MatrixXd slope = element.slope_matrix(xi * rule.points[g]) * to_eta;
    h.noalias() += (xi * element.length() * rule.weights[g]) * slope.transpose() * slope;
  }
  return h;
}

/// H_a = start_a + axis_a part.
Triple along(const Triple& start, const Eigen::Vector3d& axis, const Eigen::MatrixXd& part) {
  Triple h = start;
  for (int a = 0; a < 3; ++a)
    if (axis[a] != 0.0) h[a] += axis[a] * part;
  return h;
}

void add_point(Foreshortening& f, double mass, const Eigen::Vector3d& r, const Triple& h) {
  for (int a = 0; a < 3; ++a) {
    f.mass[a] += mass * h[a];
    for (int b = 0; b < 3; ++b)
      if (r[b] != 0.0) f.moment[3 * a + b] += (mass * r[b]) * h[a];
  }
}

}  // namespace

Foreshortening foreshortening(const Body& body, const Eigen::MatrixXd& B) {
  if (B.rows() != body.num_dofs()) throw std::invalid_argument("foreshortening: B must have num_dofs rows");
  const Eigen::Index n = B.cols();
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(n, n);
  Foreshortening f;
  f.mass = {zero, zero, zero};
  for (auto& m : f.moment) m = zero;
  f.node.assign(body.num_nodes(), Triple{zero, zero, zero});
  std::vector<char> reached(body.num_nodes(), 0);
  reached[0] = 1;

  for (int e = 0; e < body.num_elements(); ++e) {
    const ElementPlacement& placement = body.element(e);
    const auto* beam = dynamic_cast<const BeamElement*>(placement.element.get());
    if (!beam) throw std::invalid_argument("foreshortening: element " + std::to_string(e) + " is not a beam");
    const int from = placement.nodes[0], to = placement.nodes[1];
    if (!reached[from])
      throw std::invalid_argument("foreshortening: element " + std::to_string(e) + " starts at node " +
                                  std::to_string(from) + ", which no earlier element reaches from node 0");
    Eigen::MatrixXd rows(placement.dofs.size(), n);  // the element's body dofs in eta
    for (std::size_t i = 0; i < placement.dofs.size(); ++i) rows.row(i) = B.row(placement.dofs[i]);
    const Eigen::MatrixXd to_eta = placement.T * rows;
    const Eigen::Vector3d axis = placement.R.col(0);
    for (const MassPoint& p : beam->mass_points()) {
      const double xi = p.r.x() / beam->length();
      add_point(f, p.mass, placement.R * p.r + placement.origin,
                along(f.node[from], axis, slope_integral(*beam, to_eta, xi)));
    }
    if (reached[to])
      throw std::invalid_argument(
          "foreshortening: node " + std::to_string(to) +
          " is reached by two elements (a closed frame has no single path from node 0)");
    f.node[to] = along(f.node[from], axis, slope_integral(*beam, to_eta, 1.0));
    reached[to] = 1;
  }
  // The point masses: the groups after the elements', one per point mass on its node.
  const std::vector<MassPointGroup> groups = body.mass_point_groups();
  for (std::size_t g = body.num_elements(); g < groups.size(); ++g) {
    const int node = groups[g].dofs.front() / body.dofs_per_node();
    for (const MassPoint& p : groups[g].points) add_point(f, p.mass, p.r, f.node[node]);
  }
  return f;
}

}  // namespace kanegen::fem
