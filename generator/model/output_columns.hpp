// SPDX-License-Identifier: GPL-2.0-or-later
// How the model's outputs expand into named columns (a point's x, y, z; a
// loop's reaction rows; ...): defined here once, for the symbolic equations,
// the numeric derivation and verify, which must agree column for column.
#pragma once

#include <string>
#include <vector>

#include "model/model.hpp"

namespace kanegen::model {

struct OutputColumn {
  std::string name;  ///< "tip.x", "hinge_angle", "closure.f1", ...
  OutputKind kind = OutputKind::point_position;
  int output = -1;  ///< index in Model::outputs
  /// Which part of the output: 0, 1, 2 for the x, y, z of a point position
  /// or node displacement and the y, z (1, 2) of a bending moment (a planar
  /// beam's is M_z alone, 2); the row (loop_rows order) of a reaction; 0 for
  /// a scalar.
  int component = 0;
};

/// The columns of all outputs, in output order. Throws
/// std::invalid_argument for an output that names no loop (reaction) or no
/// body (bending moment), which a checked model does not have.
std::vector<OutputColumn> output_columns(const Model& model);

/// The names of a loop's equations, in their order (docs/model-format.md):
/// a planar revolute about z names its rows after the world axes.
std::vector<std::string> loop_rows(const Loop& loop);

}  // namespace kanegen::model
