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
//
// Reading a shape and differentiating it is not done here: this layer is
// Eigen only (no GiNaC, docs/architecture.md), and the slopes must be exact,
// not differenced. The caller passes a ShapeSampler: the generator's reads
// the shapes with GiNaC and differentiates them symbolically
// (symbolic/shape_function.*), the numeric path's evaluates them over dual
// numbers (numeric/shape_function.*), so each derivation keeps its own.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fem/body.hpp"
#include "model/model.hpp"

namespace kanegen::fem {

/// Samples one shape function `text` of x (names: x, L, pi and the keys of
/// `parameters`, which include L): fills value[i] and slope[i] = d/dx, exact,
/// at x[i]. Throws std::exception if the text cannot be read; a value or
/// slope it cannot evaluate (a pole) is NaN or infinite.
using ShapeSampler =
    std::function<void(const std::string& text, const std::map<std::string, double>& parameters,
                       const std::vector<double>& x, std::vector<double>& value, std::vector<double>& slope)>;

/// num_dofs x k: column j holds assumed mode j at every node of `body` (a
/// chain along link x, node positions x in 0..L): u, v, theta_z = v' and,
/// spatial, w, theta_y = -w', theta_x = theta. The parameters take
/// beam.shape_parameters. Throws model::ModelError (the component's place in
/// `file`) if a shape cannot be read or it or its slope is not finite at a node.
Eigen::MatrixXd assumed_mode_basis(const Body& body, const model::ElasticPart& beam, const std::string& file,
                                   const ShapeSampler& sample);

}  // namespace kanegen::fem
