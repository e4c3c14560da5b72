// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/axial_strain.hpp"

#include <stdexcept>

#include "fem/beam_element.hpp"
#include "fem/quadrature.hpp"

namespace kanegen::fem {

std::vector<AxialStrainElement> axial_strain_elements(const Body& body, const Eigen::MatrixXd& B) {
  if (B.rows() != body.num_dofs())
    throw std::invalid_argument("axial_strain_elements: B must have num_dofs rows");
  static const QuadratureRule rule = gauss_legendre(3);
  std::vector<AxialStrainElement> elements;
  for (int e = 0; e < body.num_elements(); ++e) {
    const ElementPlacement& placement = body.element(e);
    const auto* beam = dynamic_cast<const BeamElement*>(placement.element.get());
    if (!beam)
      throw std::invalid_argument("axial_strain_elements: element " + std::to_string(e) + " is not a beam");
    Eigen::MatrixXd rows(placement.dofs.size(), B.cols());  // the element's body dofs in eta
    for (std::size_t i = 0; i < placement.dofs.size(); ++i) rows.row(i) = B.row(placement.dofs[i]);
    const Eigen::MatrixXd to_eta = placement.T * rows;  // its own dofs u^e in eta
    const double L = beam->length();
    AxialStrainElement element;
    element.stiffness = beam->material().E * beam->section().A * L;
    // u' = (u_1 - u_0) / L: the first dof of each node is its axial displacement.
    element.axial = (to_eta.row(beam->dofs_per_node()) - to_eta.row(0)) / L;
    for (std::size_t g = 0; g < rule.points.size(); ++g) {
      element.weight.push_back(rule.weights[g]);
      element.slopes.push_back(beam->slope_matrix(rule.points[g]) * to_eta);
    }
    elements.push_back(std::move(element));
  }
  return elements;
}

}  // namespace kanegen::fem
