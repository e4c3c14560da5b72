// SPDX-License-Identifier: GPL-2.0-or-later
// Assumed modes (Rayleigh-Ritz shape functions given in the model) as a
// basis of the finite-element body that carries them: each shape is sampled
// at the nodes of a fine mesh, its values and slopes becoming the nodal dofs
// of one column, u = B eta. Mass, stiffness, inertia invariants, the tip
// mass, node outputs and joints on nodes then follow from the body as for
// nodal or modal coordinates. The mesh interpolates the shapes (Hermite
// cubics in bending, linear axially and in torsion), so the matrices are
// those of the interpolated shapes: within O(h^4) of the exact integrals in
// bending and O(h^2) axially and in torsion (docs/flexible-bodies.md).
#pragma once

#include <Eigen/Dense>
#include <string>

#include "fem/body.hpp"
#include "model/model.hpp"

namespace kanegen::fem {

/// num_dofs x k: column j holds assumed mode j at every node of `body` (a
/// chain along link x, node positions x in 0..L): u, v, theta_z = v' and,
/// spatial, w, theta_y = -w', theta_x = theta. The shapes are read by GiNaC
/// and differentiated exactly; the parameters take beam.shape_parameters.
/// Throws model::ModelError (the component's place in `file`) if a shape or
/// its slope cannot be read or is not finite at a node.
Eigen::MatrixXd assumed_mode_basis(const Body& body, const model::FlexibleBeam& beam,
                                   const std::string& file);

}  // namespace kanegen::fem
