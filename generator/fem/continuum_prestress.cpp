// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/continuum_prestress.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "fem/continuum_element.hpp"
#include "fem/invariants.hpp"
#include "fem/rigid_motions.hpp"
#include "fem/rotating.hpp"

namespace kanegen::fem {

namespace {

/// u^e = T u_b: element e's dofs in its own frame.
Eigen::VectorXd element_displacement(const Body& body, int e, const Eigen::VectorXd& u) {
  const ElementPlacement& placed = body.element(e);
  return placed.T * u(placed.dofs);
}

void check_size(const Body& body, const Eigen::VectorXd& v, const char* what) {
  if (v.size() != body.num_dofs())
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(body.num_dofs()) +
                                " body dofs, got " + std::to_string(v.size()));
}

}  // namespace

const ContinuumElement& continuum_element(const Body& body, int e) {
  const auto* element = dynamic_cast<const ContinuumElement*>(body.element(e).element.get());
  if (!element)
    throw std::invalid_argument("element " + std::to_string(e) +
                                " is not a plane or solid element: continuum prestress needs a mesh body");
  return *element;
}

Eigen::VectorXd static_displacement(const Body& body, const Constraint& held, const Eigen::VectorXd& f) {
  check_size(body, f, "static_displacement");
  return static_displacements(body, held, f);
}

Eigen::MatrixXd static_displacements(const Body& body, const Constraint& held, const Eigen::MatrixXd& loads) {
  if (loads.rows() != body.num_dofs())
    throw std::invalid_argument("static_displacements: expected " + std::to_string(body.num_dofs()) +
                                " body dofs, got " + std::to_string(loads.rows()));
  if (held.num_dofs() != body.num_dofs())
    throw std::invalid_argument("static_displacement: the constraint is for another body");
  // From the geometry: K's pivots cannot tell a thin body from a free one (rigid_motions.hpp).
  const std::string free_motion = unheld_rigid_motion(body, held);
  if (!free_motion.empty())
    throw std::invalid_argument("static_displacement: the held dofs leave the body free to move rigidly (" +
                                free_motion + "); hold a face or enough nodes to stop every rigid motion");
  const Eigen::LLT<Eigen::MatrixXd> llt(held.reduce(body.stiffness()));
  if (llt.info() != Eigen::Success)
    throw std::invalid_argument(
        "static_displacement: K is not positive definite on the free dofs although every rigid motion is "
        "held: parts of the body joined at one node or along an edge turn as a mechanism; mesh them as one");
  return held.expand(llt.solve(loads(held.free(), Eigen::all)));
}

Eigen::VectorXd centrifugal_load(const Body& body, const Eigen::Vector3d& omega) {
  const Eigen::Matrix3d w = skew(omega), w2 = w * w;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(body.num_dofs());
  for (const MassPointGroup& group : body.mass_point_groups()) {
    Eigen::VectorXd part = Eigen::VectorXd::Zero(static_cast<int>(group.dofs.size()));
    for (const MassPoint& p : group.points) part.noalias() -= p.mass * p.N.transpose() * (w2 * p.r);
    f(group.dofs) += part;
  }
  return f;
}

std::vector<ElementStress> gauss_point_stresses(const Body& body, const Eigen::VectorXd& u) {
  check_size(body, u, "gauss_point_stresses");
  std::vector<ElementStress> out;
  for (int e = 0; e < body.num_elements(); ++e) {
    const ContinuumElement& element = continuum_element(body, e);
    const Eigen::VectorXd u_e = element_displacement(body, e, u);
    ElementStress s{element.gauss_points(), {}};
    for (const Eigen::Vector3d& xi : s.xi) s.sigma.push_back(element.stress(u_e, xi));
    out.push_back(std::move(s));
  }
  return out;
}

std::function<Prestress(int element)> displacement_prestress(const Body& body, const Eigen::VectorXd& u) {
  check_size(body, u, "displacement_prestress");
  auto fields = std::make_shared<std::vector<Prestress>>();
  for (int e = 0; e < body.num_elements(); ++e) {
    continuum_element(body, e);  // refuses other elements here, not when K_sigma is formed
    // Shares the element, so the field outlives neither it nor the body.
    auto element = std::static_pointer_cast<const ContinuumElement>(body.element(e).element);
    Prestress p;
    p.stress = [element, u_e = element_displacement(body, e, u)](const Eigen::Vector3d& xi) {
      return element->stress(u_e, xi);
    };
    fields->push_back(std::move(p));
  }
  return [fields](int e) { return fields->at(e); };
}

Eigen::MatrixXd load_geometric_stiffness(const Body& body, const Constraint& held, const Eigen::VectorXd& f) {
  return body.geometric_stiffness(displacement_prestress(body, static_displacement(body, held, f)));
}

Eigen::MatrixXd spinning_stiffness(const Body& body, const Constraint& held, const Eigen::Vector3d& omega,
                                   bool with_spin_softening) {
  Eigen::MatrixXd k = body.stiffness() + load_geometric_stiffness(body, held, centrifugal_load(body, omega));
  if (with_spin_softening) k += spin_softening(body_invariants(body), omega);
  return k;
}

}  // namespace kanegen::fem
