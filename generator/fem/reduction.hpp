// SPDX-License-Identifier: GPL-2.0-or-later
// One flexible body as the generator will take it: elastic coordinates eta
// (the free nodal dofs, or the amplitudes of the first k modes or of given
// shapes), u = B eta,
// and every matrix and invariant in those coordinates.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "fem/body.hpp"
#include "fem/boundary.hpp"
#include "fem/invariants.hpp"
#include "fem/rotating.hpp"

namespace kanegen::fem {

struct ReducedBody {
  Eigen::MatrixXd basis;           ///< num_dofs x n: B, u = B eta (B = P, or P Phi)
  std::vector<std::string> names;  ///< n: "n3.v", "n3.theta_z", ... or "mode1", "mode2", ...
  Eigen::MatrixXd mass;            ///< n x n: B^T M B
  Eigen::MatrixXd stiffness;       ///< n x n: B^T K_e B
  InertiaInvariants invariants;    ///< in eta
  std::optional<GeometricStiffnessBasis> geometric;  ///< n x n each; only for a beam chain on link x
  Eigen::VectorXd omega;                             ///< modal: the kept frequencies (rad/s); nodal: empty

  /// 3 x n: the node's displacement (rotation) in the link frame in terms of eta.
  Eigen::MatrixXd node_translation(const Body& body, int node) const {
    return body.node_translation(node) * basis;
  }
  Eigen::MatrixXd node_rotation(const Body& body, int node) const { return body.node_rotation(node) * basis; }
};

/// Nodal coordinates: the constraint's free dofs, named "n<node>.<u|v|w|theta_x|theta_y|theta_z>"
/// (link-frame components).
ReducedBody reduce_nodal(const Body& body, const Constraint& constraint);
/// Modal coordinates: the first `modes` modes of the constrained body (canonical orientation).
ReducedBody reduce_modal(const Body& body, const Constraint& constraint, int modes);
/// Given shapes (assumed modes): u = basis eta, basis num_dofs x k, no
/// constraint (the shapes carry it); named "mode1", ... as modal coordinates.
ReducedBody reduce_assumed(const Body& body, Eigen::MatrixXd basis);

}  // namespace kanegen::fem
