// SPDX-License-Identifier: GPL-2.0-or-later
// The force elements of a model besides constant forces: springs between
// two points (forces at the points, an energy) and joint efforts (a
// generalized force on one coordinate).
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "kinematics/tree_kinematics.hpp"
#include "model/model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

/// A force at a point of a body, both in the body's axes.
struct PointLoad {
  int state = -1;  ///< index in TreeKinematics::bodies()
  symbolic::Vec3 at;
  symbolic::Vec3 force;
};

/// What a spring does: a force at each end on a body (none on the ground)
/// and its potential energy k (l - l0)^2 / 2; the damper's power -c l_dot^2.
struct SpringLoads {
  std::vector<PointLoad> loads;
  GiNaC::ex energy;
  GiNaC::ex damping_power;
};

/// The spring's forces F = -(k (l - l0) + c l_dot) d / l on the first point
/// and -F on the second, d = p1 - p2 in world axes, l = |d|,
/// l_dot = d.(v1 - v2) / l. Singular at l = 0 (documented: the model gives
/// no direction there).
SpringLoads spring_loads(const model::Spring& spring, const kinematics::TreeKinematics& tree,
                         const symbolic::Variables& vars, symbolic::Program& program);

/// The generalized force of a joint effort: its value, which may depend on t.
GiNaC::ex joint_effort_value(const model::JointEffort& effort, const symbolic::Variables& vars);

}  // namespace kanegen::kane
