// A flexible body of the model (model::FlexibleBeam) as the finite-element
// layer's reduced body: nodes along the segments, beam elements, the tip
// mass, the support, nodal or modal coordinates or assumed modes, and the
// damping matrix.
// This is the bridge from the plain model data to the generator.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "fem/body.hpp"
#include "fem/beam_element.hpp"
#include "fem/reduction.hpp"
#include "model/model.hpp"

namespace kanegen::fem {

struct ModelBeam {
  Body body;             ///< all nodal dofs, link frame
  ReducedBody reduced;   ///< the elastic coordinates eta: u = basis eta
  Eigen::MatrixXd damping;  ///< n x n: alpha M + beta K, or 2 zeta omega_i in modal coordinates
  /// The section and material of every element, for the stress outputs.
  BeamSection section;
  Material material;
};

/// Builds the body; throws model::ModelError (naming the body's place) when
/// the beam cannot be built, e.g. geometric stiffening asked for a beam that
/// is not one straight run along the link x axis.
ModelBeam build_model_beam(const model::Body& body, const std::string& file);

}  // namespace kanegen::fem
