// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/rotating.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fem/beam_element.hpp"

namespace kanegen::fem {

namespace {

struct Segment {
  double x0, x1, rho_a;
};

std::vector<Segment> chain_segments(const Body& body) {
  if (!is_beam_chain(body))
    throw std::invalid_argument(
        "chain_axial_force: every element must be a beam on the link x axis, along +x");
  std::vector<Segment> segments;
  for (int e = 0; e < body.num_elements(); ++e) {
    const ElementPlacement& placed = body.element(e);
    const auto& beam = static_cast<const BeamElement&>(*placed.element);
    segments.push_back({placed.origin.x(), placed.origin.x() + beam.length(), beam.mass_per_length()});
  }
  return segments;
}

}  // namespace

bool is_beam_chain(const Body& body) {
  for (int e = 0; e < body.num_elements(); ++e) {
    const ElementPlacement& placed = body.element(e);
    const auto* beam = dynamic_cast<const BeamElement*>(placed.element.get());
    if (!beam || (placed.R.col(0) - Eigen::Vector3d::UnitX()).norm() > 1e-9 ||
        std::abs(placed.origin.y()) + std::abs(placed.origin.z()) > 1e-9 * beam->length())
      return false;
  }
  return body.num_elements() > 0;
}

std::function<Prestress(int element)> chain_axial_force(const Body& body, double a_const, double a_lin,
                                                        double tip_force) {
  auto segments = std::make_shared<const std::vector<Segment>>(chain_segments(body));
  // Point masses enter through their mass points (r, mass); elements' own points are skipped.
  auto masses = std::make_shared<std::vector<std::pair<double, double>>>();
  const auto groups = body.mass_point_groups();
  for (std::size_t g = static_cast<std::size_t>(body.num_elements()); g < groups.size(); ++g)
    for (const MassPoint& p : groups[g].points) masses->emplace_back(p.r.x(), p.mass);

  auto axial_force_at = [segments, masses, a_const, a_lin, tip_force](double x) {
    double n = tip_force;
    for (const Segment& s : *segments) {
      const double lo = std::max(x, s.x0), hi = s.x1;
      if (hi > lo) n += s.rho_a * (a_const * (hi - lo) + 0.5 * a_lin * (hi * hi - lo * lo));
    }
    for (const auto& [xm, m] : *masses)
      if (xm > x) n += m * (a_const + a_lin * xm);
    return n;
  };
  return [segments, axial_force_at](int e) {
    const Segment s = segments->at(e);
    return Prestress{[s, axial_force_at](double xi) { return axial_force_at(s.x0 + xi * (s.x1 - s.x0)); }};
  };
}

GeometricStiffnessBasis geometric_stiffness_basis(const Body& body) {
  return {body.geometric_stiffness(chain_axial_force(body, 1.0, 0.0, 0.0)),
          body.geometric_stiffness(chain_axial_force(body, 0.0, 1.0, 0.0)),
          body.geometric_stiffness(chain_axial_force(body, 0.0, 0.0, 1.0))};
}

Eigen::MatrixXd node_force_geometric_stiffness(const Body& body, int node) {
  if (!is_beam_chain(body)) throw std::invalid_argument("node_force_geometric_stiffness: not a beam chain");
  const double x = body.node_position(node).x();
  return body.geometric_stiffness([&](int e) {
    // The element carries the force if it lies before the node.
    const double start = body.node_position(body.element(e).nodes[0]).x();
    const double end = body.node_position(body.element(e).nodes[1]).x();
    const double n = std::max(start, end) <= x + 1e-12 * std::abs(x) ? 1.0 : 0.0;
    return Prestress{[n](double) { return n; }};
  });
}

Eigen::MatrixXd spin_softening(const InertiaInvariants& inv, const Eigen::Vector3d& omega) {
  const Eigen::Matrix3d w = skew(omega), w2 = w * w;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(inv.n, inv.n);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) k += w2(a, b) * inv.S_nn[3 * a + b];
  return k;
}

Eigen::MatrixXd rotating_stiffness(const Body& body, const Eigen::Vector3d& omega, bool with_spin_softening) {
  const double a_lin = omega.y() * omega.y() + omega.z() * omega.z();
  Eigen::MatrixXd k = body.stiffness() + body.geometric_stiffness(chain_axial_force(body, 0.0, a_lin));
  if (with_spin_softening) k += spin_softening(body_invariants(body), omega);
  return k;
}

}  // namespace kanegen::fem
