// SPDX-License-Identifier: GPL-2.0-or-later
// The loop-closure equations of the model's closed loops: Phi(q) = 0, their
// Jacobian C = dPhi/dq (q_dot = u for every coordinate) and the bias gamma of
// the acceleration level, C u_dot = gamma = -(dC/dt) u.
//
// Phi is built from the world poses of the tree, with the Program's
// intermediates written out so that it can be differentiated: loops are
// short (a few bodies each), so the expressions stay small.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "fem/elastic_model.hpp"
#include "kinematics/tree_kinematics.hpp"
#include "model/model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::kane {

struct LoopConstraints {
  std::vector<GiNaC::ex> phi;       ///< nc
  std::vector<GiNaC::ex> jacobian;  ///< nc * nu, row-major
  std::vector<GiNaC::ex> bias;      ///< nc: gamma, with every speed's acceleration on the left
  std::vector<std::string> names;   ///< per row: "<loop>.x", "<loop>.f1", "<loop>.m1", ...
  std::vector<std::string> loops;   ///< per row: the loop's name
  int size() const { return static_cast<int>(phi.size()); }
};

/// The rows of every loop of `model`, in file order. Throws
/// model::ModelError for what the kinematics cannot express (a spatial
/// revolute on a beam node).
LoopConstraints derive_loop_constraints(const model::Model& model, const symbolic::Variables& vars,
                                        const symbolic::Program& program,
                                        const kinematics::TreeKinematics& tree,
                                        const std::map<int, fem::ElasticModel>& flexible);

}  // namespace kanegen::kane
