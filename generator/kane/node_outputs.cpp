// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/node_outputs.hpp"

#include <stdexcept>

#include "fem/beam_element.hpp"
#include "kane/beam_node.hpp"
#include "kane/flexible_body.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::kane {
namespace {

using GiNaC::ex;

/// Rows of section resultants at `node` as maps of eta: planar (N, M_z),
/// spatial (N, T, M_y, M_z), from the element that starts there (or ends
/// there, for the last node), whose index goes to `element_index`.
Eigen::MatrixXd resultants_at(const fem::ElasticModel& beam, int node, int& element_index) {
  const fem::Body& body = beam.body;
  for (int pass = 0; pass < 2; ++pass)
    for (int e = 0; e < body.num_elements(); ++e) {
      const fem::ElementPlacement& placement = body.element(e);
      if (placement.nodes[pass] != node) continue;
      const auto* element = dynamic_cast<const fem::BeamElement*>(placement.element.get());
      if (!element) throw std::logic_error("node outputs: not a beam element");
      element_index = e;
      Eigen::MatrixXd rows(placement.dofs.size(), beam.reduced.basis.cols());
      for (std::size_t i = 0; i < placement.dofs.size(); ++i)
        rows.row(i) = beam.reduced.basis.row(placement.dofs[i]);
      return element->resultant_matrix(pass == 0 ? 0.0 : 1.0) * placement.T * rows;
    }
  throw std::logic_error("node outputs: node without an element");
}

ex row_times(const Eigen::MatrixXd& m, int row, const std::vector<ex>& eta) {
  return linear_combination(cleaned(m.row(row).transpose()), eta);
}

}  // namespace

NodeOutputs node_outputs(const model::Body& body, const fem::ElasticModel& beam, const model::Output& output,
                         const std::vector<ex>& eta, symbolic::Program& program) {
  NodeOutputs out;
  const bool spatial = body.elastic.formulation == model::BeamFormulation::spatial;
  const std::string& name = output.name;
  if (output.kind == model::OutputKind::node_displacement) {
    const NodePoint node = node_point(beam, output.node, eta, &program);  // foreshortening included
    const char* axes[] = {".x", ".y", ".z"};
    for (int a = 0; a < 3; ++a) {
      out.values.push_back(node.displacement[a]);
      out.names.push_back(name + axes[a]);
    }
    return out;
  }
  int element = 0;
  const Eigen::MatrixXd r = resultants_at(beam, output.node, element);
  ex axial = row_times(r, 0, eta);
  if (!beam.axial_strain.empty()) {
    // The nonlinear axial strain: N = EA (u' + phi_e), phi_e = 1/2 sum_p w_p |slopes_p eta|^2.
    const fem::AxialStrainElement& e = beam.axial_strain[static_cast<std::size_t>(element)];
    ex phi = 0;
    for (std::size_t p = 0; p < e.slopes.size(); ++p)
      for (Eigen::Index j = 0; j < e.slopes[p].rows(); ++j) {
        const ex slope = row_times(e.slopes[p], static_cast<int>(j), eta);
        phi += symbolic::number(e.weight[p] / 2) * slope * slope;
      }
    const auto* beam_element =
        dynamic_cast<const fem::BeamElement*>(beam.body.element(element).element.get());
    const double ea = e.stiffness / beam_element->length();
    axial = program.define(axial + symbolic::number(ea) * phi);
  }
  const ex moment_z = row_times(r, spatial ? 3 : 1, eta);
  const ex moment_y = spatial ? row_times(r, 2, eta) : ex(0);
  switch (output.kind) {
    case model::OutputKind::axial_force:
      out.values = {axial};
      out.names = {name};
      break;
    case model::OutputKind::bending_moment:
      if (spatial) {
        out.values = {moment_y, moment_z};
        out.names = {name + ".y", name + ".z"};
      } else {
        out.values = {moment_z};
        out.names = {name};
      }
      break;
    default: {  // bending_stress: the extreme fibre's |N/A| + |M_z| y/Iz + |M_y| z/Iy
      const model::ElasticPart& f = body.elastic;
      ex stress = GiNaC::abs(axial) / symbolic::number(f.A) +
                  GiNaC::abs(moment_z) * symbolic::number(f.fibre_y / f.Iz);
      if (spatial) stress += GiNaC::abs(moment_y) * symbolic::number(f.fibre_z / f.Iy);
      out.values = {stress};
      out.names = {name};
    }
  }
  return out;
}

}  // namespace kanegen::kane
