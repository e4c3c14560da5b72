// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/force_elements.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using GiNaC::ex;

Vec3 vec(const Variables& vars, const model::Vec3& v) {
  return {vars.scalar(v[0]), vars.scalar(v[1]), vars.scalar(v[2])};
}

/// One end of a spring: its world position and velocity, and the body state
/// it moves with (-1: fixed in the ground, where the point is in world axes).
struct End {
  int state = -1;
  Vec3 local, position, velocity;
};

End end_of(const std::string& body, const model::Vec3& point, const kinematics::TreeKinematics& tree,
           const Variables& vars, Program& program) {
  End e;
  e.state = tree.state_of(body);
  e.local = vec(vars, point);
  if (e.state < 0) {
    e.position = e.local;
    e.velocity = zero_vec();
    return e;
  }
  const kinematics::BodyState& b = tree.bodies()[e.state];
  e.position = tree.world_point(b, e.local);
  e.velocity = named(program, mul(b.rotation, b.velocity + cross(b.omega, e.local)));
  return e;
}

}  // namespace

SpringLoads spring_loads(const model::Spring& spring, const kinematics::TreeKinematics& tree,
                         const Variables& vars, Program& program) {
  const End first = end_of(spring.body, spring.point, tree, vars, program);
  const End second = end_of(spring.body2, spring.point2, tree, vars, program);
  const Vec3 d = named(program, first.position - second.position);
  // l depends on q only, so that the potential energy kernel (no u) can use it.
  const ex length = program.define(sqrt(dot(d, d)));
  const ex stiffness = vars.scalar(spring.stiffness), rest = vars.scalar(spring.rest_length);
  const ex damping = vars.scalar(spring.damping);
  const ex stretch = length - rest;
  // (k (l - l0) + c l_dot) / l with l_dot = d.(v1 - v2) / l; for l0 = 0 and
  // c = 0 GiNaC cancels it to k, and the force -k d stays regular at l = 0.
  const ex rate = dot(d, first.velocity - second.velocity) / length;  // l_dot
  const ex pull = program.define((stiffness * stretch + damping * rate) / length);
  const Vec3 force = named(program, zero_vec() - pull * d);  // on the first point, world axes

  SpringLoads out;
  out.energy = stiffness * stretch * stretch / 2;
  out.damping_power = -damping * rate * rate;
  for (const End* e : {&first, &second}) {
    if (e->state < 0) continue;
    const Vec3 f = mul_transposed(tree.bodies()[e->state].rotation, e == &first ? force : zero_vec() - force);
    out.loads.push_back({e->state, e->local, named(program, f)});
  }
  return out;
}

ex joint_effort_value(const model::JointEffort& effort, const Variables& vars) {
  return effort.value.is_literal ? vars.scalar(effort.value)
                                 : vars.time_expression(effort.value.text, effort.value.where);
}

}  // namespace kanegen::kane
