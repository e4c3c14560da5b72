// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/reduction.hpp"

#include <stdexcept>

#include "fem/modal.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_modal.hpp"

namespace kanegen::fem {

namespace {

const char* kind_name(DofKind kind) {
  switch (kind) {
    case DofKind::kUx:
      return "u";
    case DofKind::kUy:
      return "v";
    case DofKind::kUz:
      return "w";
    case DofKind::kRx:
      return "theta_x";
    case DofKind::kRy:
      return "theta_y";
    case DofKind::kRz:
      return "theta_z";
  }
  return "?";
}

ReducedBody reduce_with(const Body& body, Eigen::MatrixXd basis, std::vector<std::string> names) {
  ReducedBody r;
  if (use_sparse_path(body.num_dofs(), ModalPath::kAuto)) {  // no dense num_dofs x num_dofs matrix
    r.mass = basis.transpose() * (sparse_mass(body) * basis);
    r.stiffness = basis.transpose() * (sparse_stiffness(body) * basis);
  } else {
    r.mass = basis.transpose() * body.mass() * basis;
    r.stiffness = basis.transpose() * body.stiffness() * basis;
  }
  r.invariants = transform(body_invariants(body), basis);
  if (is_beam_chain(body)) {
    const GeometricStiffnessBasis full = geometric_stiffness_basis(body);
    r.geometric = GeometricStiffnessBasis{basis.transpose() * full.uniform * basis,
                                          basis.transpose() * full.linear * basis,
                                          basis.transpose() * full.tip * basis};
  }
  r.basis = std::move(basis);
  r.names = std::move(names);
  return r;
}

}  // namespace

ReducedBody reduce_nodal(const Body& body, const Constraint& constraint) {
  if (constraint.num_dofs() != body.num_dofs()) throw std::invalid_argument("reduce_nodal: constraint size");
  std::vector<std::string> names;
  for (int d : constraint.free())
    names.push_back("n" + std::to_string(d / body.dofs_per_node()) + "." +
                    kind_name(body.layout()[d % body.dofs_per_node()]));
  return reduce_with(body, constraint.selection(), std::move(names));
}

ReducedBody reduce_modal(const Body& body, const Constraint& constraint, int modes) {
  if (constraint.num_dofs() != body.num_dofs()) throw std::invalid_argument("reduce_modal: constraint size");
  if (modes < 1 || modes > constraint.num_free()) throw std::invalid_argument("reduce_modal: bad mode count");
  const ModalBasis m = constrained_modes(body, constraint, modes);  // dense or sparse by size
  std::vector<std::string> names;
  for (int i = 1; i <= modes; ++i) names.push_back("mode" + std::to_string(i));
  ReducedBody r = reduce_with(body, constraint.expand(m.shapes), std::move(names));
  r.omega = m.omega;
  return r;
}

ReducedBody reduce_assumed(const Body& body, Eigen::MatrixXd basis) {
  if (basis.rows() != body.num_dofs()) throw std::invalid_argument("reduce_assumed: basis size");
  std::vector<std::string> names;
  for (Eigen::Index i = 1; i <= basis.cols(); ++i) names.push_back("mode" + std::to_string(i));
  return reduce_with(body, std::move(basis), std::move(names));
}

}  // namespace kanegen::fem
