// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/model_mesh.hpp"

#include <fstream>

#include "fem/reduction.hpp"
#include "model/model_error.hpp"

namespace kanegen::fem {

namespace {

using model::ModelError;

/// Reruns `f`, turning a mesh-layer error (it names the mesh file) into one
/// that names the model's place as well.
template <class F>
auto at_model_place(const std::string& model_file, const std::string& place, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const ModelError& e) {
    throw ModelError(model_file, place, e.what(), "");
  }
}

}  // namespace

InpMesh read_model_mesh(const model::Body& body, const std::string& model_file) {
  const model::MeshSource& m = body.beam.mesh;
  if (!std::ifstream(m.path))
    throw ModelError(model_file, m.where + "/file",
                     "cannot open the mesh file '" + m.path + "' of body '" + body.name + "'",
                     "give the .inp file's path relative to the model file");
  return read_inp_mesh_file(m.path);
}

MeshBody build_model_mesh_body(const model::Body& body, const InpMesh& mesh, const std::string& model_file) {
  const model::FlexibleBeam& f = body.beam;
  const ContinuumMaterial material{f.E, f.mesh.poisson, f.density};
  return at_model_place(model_file, f.mesh.where + "/element_set", [&] {
    return build_mesh_body(mesh, material, f.mesh.thickness, f.mesh.element_set);
  });
}

ModelBeam build_model_mesh(const model::Body& body, const std::string& model_file) {
  const model::FlexibleBeam& f = body.beam;
  const InpMesh mesh = read_model_mesh(body, model_file);
  const MeshBody mb = build_model_mesh_body(body, mesh, model_file);
  const Constraint constraint = f.support == model::BeamSupport::free
                                    ? Constraint(mb.body.num_dofs(), {})
                                    : at_model_place(model_file, f.mesh.where + "/clamped_set",
                                                     [&] { return mb.clamped(mesh, f.mesh.clamped_set); });
  if (f.modes > constraint.num_free())
    throw ModelError(model_file, f.where + "/modes",
                     "body '" + body.name + "' has " + std::to_string(constraint.num_free()) +
                         " free dofs, fewer than the " + std::to_string(f.modes) + " modes asked for",
                     "keep fewer modes, or refine the mesh");
  ModelBeam out{mb.body, {}, {}, {}, {}, {}, std::nullopt};
  if (f.support == model::BeamSupport::free) {
    // The joint carries the rigid motions: the free-free body's first modes
    // (3 in the plane, 6 in space, omega = 0) would duplicate them.
    const int rigid = out.body.dofs_per_node() == 2 ? 3 : 6;
    if (f.modes + rigid > constraint.num_free())
      throw ModelError(
          model_file, f.where + "/modes",
          "body '" + body.name + "' has too few dofs for " + std::to_string(f.modes) + " elastic modes",
          "keep fewer modes, or refine the mesh");
    const ReducedBody all = reduce_modal(out.body, constraint, f.modes + rigid);
    out.reduced = reduce_assumed(out.body, all.basis.rightCols(f.modes));
    out.reduced.omega = all.omega.tail(f.modes);
  } else {
    out.reduced = reduce_modal(out.body, constraint, f.modes);
  }
  const int n = static_cast<int>(out.reduced.names.size());
  if (f.modal_damping > 0) {
    out.damping = Eigen::MatrixXd::Zero(n, n);
    for (int k = 0; k < n; ++k)
      out.damping(k, k) = 2.0 * f.modal_damping * out.reduced.omega(k) * out.reduced.mass(k, k);
  } else {
    out.damping = f.rayleigh_alpha * out.reduced.mass + f.rayleigh_beta * out.reduced.stiffness;
  }
  return out;
}

}  // namespace kanegen::fem
