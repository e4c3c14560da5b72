#include "fem/model_beam.hpp"

#include "fem/assumed_modes.hpp"
#include "fem/beam_body.hpp"
#include "fem/boundary.hpp"
#include "fem/rotating.hpp"
#include "model/model_error.hpp"

namespace kanegen::fem {

ModelBeam build_model_beam(const model::Body& body, const std::string& file) {
  const model::FlexibleBeam& f = body.beam;
  const bool planar = f.formulation == model::BeamFormulation::planar;
  BeamProperties properties;
  properties.kind = planar ? BeamKind::kPlanar : BeamKind::kSpatial;
  properties.section.A = f.A;
  properties.section.Iy = planar ? 0.0 : f.Iy;
  properties.section.Iz = f.Iz;
  properties.section.J = planar ? 0.0 : f.J;
  properties.material = {f.E, f.G, f.density};

  ModelBeam out{
      Body(planar ? planar_layout() : spatial_layout()), {}, {}, properties.section, properties.material};
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
    out.reduced = reduce_assumed(out.body, assumed_mode_basis(out.body, f, file));
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
  if (f.geometric_stiffening && !out.reduced.geometric)
    throw model::ModelError(
        file, f.where + "/geometric_stiffening",
        "geometric stiffening is available only for a beam that is one straight run along the "
        "body's +x axis (body '" +
            body.name + "')",
        "set \"geometric_stiffening\": false, or lay the beam along x");

  const int n = static_cast<int>(out.reduced.names.size());
  if (f.modes > 0 && f.modal_damping > 0) {
    out.damping = Eigen::MatrixXd::Zero(n, n);
    for (int k = 0; k < n; ++k)
      out.damping(k, k) = 2.0 * f.modal_damping * out.reduced.omega(k) * out.reduced.mass(k, k);
  } else {
    out.damping = f.rayleigh_alpha * out.reduced.mass + f.rayleigh_beta * out.reduced.stiffness;
  }
  return out;
}

}  // namespace kanegen::fem
