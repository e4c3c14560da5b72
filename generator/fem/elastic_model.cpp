// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/elastic_model.hpp"

#include "fem/assumed_modes.hpp"
#include "fem/beam_body.hpp"
#include "fem/boundary.hpp"
#include "fem/model_mesh.hpp"
#include "model/model_error.hpp"

namespace kanegen::fem {

Eigen::MatrixXd reduced_damping(const model::ElasticPart& f, const ReducedBody& reduced, bool modal) {
  if (!(modal && f.modal_damping > 0))
    return f.rayleigh_alpha * reduced.mass + f.rayleigh_beta * reduced.stiffness;
  const int n = static_cast<int>(reduced.names.size());
  Eigen::MatrixXd damping = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) damping(k, k) = 2.0 * f.modal_damping * reduced.omega(k) * reduced.mass(k, k);
  return damping;
}

ElasticModel build_elastic_model(const model::Body& body, const std::string& file,
                                 const ShapeSampler& shapes) {
  if (body.elastic.mesh.present()) return build_model_mesh(body, file);
  const model::ElasticPart& f = body.elastic;
  const bool planar = f.formulation == model::BeamFormulation::planar;
  BeamProperties properties;
  properties.kind = planar ? BeamKind::kPlanar : BeamKind::kSpatial;
  properties.section.A = f.A;
  properties.section.Iy = planar ? 0.0 : f.Iy;
  properties.section.Iz = f.Iz;
  properties.section.J = planar ? 0.0 : f.J;
  properties.material = {f.E, f.G, f.density};

  ElasticModel out{Body(planar ? planar_layout() : spatial_layout()),
                   {},
                   {},
                   properties.section,
                   properties.material,
                   {},
                   std::nullopt,
                   {},
                   false,
                   {}};
  int last = out.body.add_node(Eigen::Vector3d::Zero());
  for (const model::BeamSegment& s : f.segments)
    last = add_beam_run(out.body, last, Eigen::Vector3d(s.to[0], s.to[1], s.to[2]), s.elements, properties);
  if (f.tip_mass > 0) {
    const auto& i = f.tip_inertia;
    Eigen::Matrix3d inertia;
    inertia << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
    out.body.add_point_mass(last, f.tip_mass, inertia);
  }
  if (!f.assumed_modes.empty()) {
    out.reduced = reduce_assumed(out.body, assumed_mode_basis(out.body, f, file, shapes));
    // check_model has made the sampled shapes independent; this guards the
    // exact basis (a shape independent only through its finite-difference slope).
    if (out.reduced.mass.llt().info() != Eigen::Success)
      throw model::ModelError(file, f.where + "/assumed_modes",
                              "the mass matrix of the assumed modes of body '" + body.name +
                                  "' is singular: the shapes are linearly dependent at the nodes",
                              "remove the dependent shapes, or give more \"elements\"");
  } else {
    const Support support = f.support == model::BeamSupport::clamped         ? Support::kClamped
                            : f.support == model::BeamSupport::pinned_pinned ? Support::kPinnedPinned
                                                                             : Support::kFree;
    const Constraint constraint = support_constraint(out.body, support);
    out.reduced =
        f.modes > 0 ? reduce_modal(out.body, constraint, f.modes) : reduce_nodal(out.body, constraint);
  }
  if (f.geometric_stiffening) {
    if (f.modes > 0 || !f.assumed_modes.empty()) {
      // Kept to second order, the foreshortening of a bent beam moves its
      // later legs along their own bending (a first-order coupling in the
      // elastic block that the truncation drops): the mass matrix then loses
      // definiteness at deflections of a millimetre. A straight beam has none.
      for (int e = 1; e < out.body.num_elements(); ++e)
        if (!out.body.element(e).R.col(0).isApprox(out.body.element(0).R.col(0), 1e-12))
          throw model::ModelError(
              file, f.where + "/geometric_stiffening",
              "geometric stiffening of a beam in modes needs a straight beam, and body '" + body.name +
                  "' turns at its element " + std::to_string(e) +
                  " (its modal foreshortening would not keep the "
                  "mass matrix positive definite)",
              "give the beam in nodal coordinates (remove \"modes\"), where the stiffening is the nonlinear "
              "axial strain and any shape works, or set \"geometric_stiffening\": false");
      // The segments run on from node 0, so every element starts at a node already reached.
      out.foreshortening = foreshortening(out.body, out.reduced.basis);
    } else {
      out.axial_strain = axial_strain_elements(out.body, out.reduced.basis);
    }
  }

  out.damping = reduced_damping(f, out.reduced, f.modes > 0);
  return out;
}

}  // namespace kanegen::fem
