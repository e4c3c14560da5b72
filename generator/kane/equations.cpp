// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/equations.hpp"

#include <map>
#include <stdexcept>

#include "kane/beam_node.hpp"
#include "kane/flexible_body.hpp"
#include "kane/force_elements.hpp"
#include "kane/node_outputs.hpp"
#include "kinematics/tree_kinematics.hpp"
#include "model/model_error.hpp"
#include "model/output_columns.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using GiNaC::ex;
using symbolic::Mat3;
using symbolic::Vec3;

Vec3 vec(const symbolic::Variables& vars, const model::Vec3& v) {
  return {vars.scalar(v[0]), vars.scalar(v[1]), vars.scalar(v[2])};
}

/// Mass, first moment h = m c and second moment K = I + m (|c|^2 1 - c c^T)
/// of a set of bodies about a body frame's origin, in its axes: enough to
/// give the momentum of the set moving as one rigid body.
struct SpatialInertia {
  ex mass = 0;
  Vec3 moment = zero_vec();
  Mat3 second = Mat3{0, 0, 0, 0, 0, 0, 0, 0, 0};
};

/// Resultant moment (about a body frame's origin) and force, in its axes.
struct Wrench {
  Vec3 moment = zero_vec();
  Vec3 force = zero_vec();
};

/// A set's inertia about the parent frame's origin, in parent axes, given it
/// in the child frame (E: parent -> child axes, r: parent origin -> child origin).
SpatialInertia to_parent(Program& program, const SpatialInertia& c, const Mat3& to_child, const Vec3& r) {
  const Vec3 h = named(program, mul_transposed(to_child, c.moment));
  // E^T K E is symmetric: six entries, not nine.
  const Mat3 ke = named(program, mul(c.second, to_child));
  Mat3 k;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      k[3 * i + j] = k[3 * j + i] =
          program.define(to_child[i] * ke[j] + to_child[3 + i] * ke[3 + j] + to_child[6 + i] * ke[6 + j]);
  SpatialInertia p;
  p.mass = c.mass;
  p.moment = h + c.mass * r;
  // Sum of m (|r + x|^2 1 - (r + x)(r + x)^T) over the set, x = its points.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      p.second[3 * i + j] = k[3 * i + j] + (i == j ? c.mass * dot(r, r) + 2 * dot(r, h) : ex(0)) -
                            c.mass * r[i] * r[j] - r[i] * h[j] - h[i] * r[j];
  return p;
}

/// A wrench about the parent frame's origin, in parent axes.
Wrench to_parent(Program& program, const Wrench& w, const Mat3& to_child, const Vec3& r) {
  const Vec3 f = named(program, mul_transposed(to_child, w.force));
  return {named(program, mul_transposed(to_child, w.moment) + cross(r, f)), f};
}

/// A subtree on a node of flexible body P moves rigidly with P's elastic
/// speeds (twists w_k, v_k about P's origin): it adds its momentum to theirs,
/// its share of their mass block and its wrench to their forcing.
/// `inertia` and `wrench`: the subtree's, about P's origin in P's axes.
void add_node_subtree(FlexibleTerms& p, const kinematics::BodyState& child, const SpatialInertia& inertia,
                      const Wrench& wrench, Program& program) {
  const std::size_t n = child.node_partial_angular.size();
  std::vector<Vec3> angular(n), linear(n);
  for (std::size_t l = 0; l < n; ++l) {
    const Vec3& w = child.node_partial_angular[l];
    const Vec3& v = child.node_partial_linear[l];
    angular[l] = named(program, mul(inertia.second, w) + cross(inertia.moment, v));
    linear[l] = named(program, inertia.mass * v + cross(w, inertia.moment));
  }
  const std::size_t count = p.elastic_forcing.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& w = child.node_partial_angular[k];
    const Vec3& v = child.node_partial_linear[k];
    for (std::size_t l = 0; l < n; ++l)
      p.elastic_mass[k * count + l] += dot(w, angular[l]) + dot(v, linear[l]);
    p.elastic_forcing[k] += dot(w, wrench.moment) + dot(v, wrench.force);
  }
  for (std::size_t l = 0; l < n; ++l) {
    p.angular_momentum[l] = p.angular_momentum[l] + angular[l];
    p.linear_momentum[l] = p.linear_momentum[l] + linear[l];
  }
}

}  // namespace

Equations derive_equations(const model::Model& model, const symbolic::Variables& vars,
                           symbolic::Program& program, MassMatrixMethod method,
                           const FlexibleBodies& flexible) {
  // Joints on nodes of flexible parents.
  std::map<int, kinematics::NodeAttachment> attachments;
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const model::Joint& j = model.joints[k];
    if (j.parent_node < 0) continue;
    int parent = -1;
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == j.parent) parent = static_cast<int>(b);
    if (j.type == model::JointType::prismatic)
      throw model::ModelError(model.source_file, j.where + "/parent_node",
                              "only revolute, continuous and fixed joints on beam nodes are supported",
                              "attach prismatic joint '" + j.name +
                                  "' to the body frame (remove \"parent_node\"), or put a fixed joint "
                                  "and a body on the node and the slide on that body");
    const fem::ModelBeam& beam = flexible.at(parent);
    kinematics::NodeAttachment a;
    a.position = beam.body.node_position(j.parent_node);
    a.translation = beam.reduced.node_translation(beam.body, j.parent_node);
    a.rotation = beam.reduced.node_rotation(beam.body, j.parent_node);
    a.first = vars.elastic_first[parent];
    if (beam.foreshortening) {
      const auto& h = beam.foreshortening->node[j.parent_node];
      a.shortening.assign(h.begin(), h.end());
    }
    attachments.emplace(static_cast<int>(k), a);
  }
  // The world-axes sum of M does not know the nodes' partial velocities.
  if (!attachments.empty()) method = MassMatrixMethod::body_frames;
  const Vec3 gravity = vec(vars, model.gravity);
  // The ground accelerates at -g: every rest acceleration then carries gravity.
  const kinematics::TreeKinematics tree(model, vars, program, zero_vec() - gravity, attachments);
  Equations eq;
  eq.nq = eq.nu = static_cast<int>(vars.q.size());
  std::map<std::size_t, FlexibleTerms> elastic;  // by state index
  const int n = eq.nu;
  eq.mass_matrix.assign(n * n, 0);
  eq.forcing.assign(n, 0);
  eq.kinetic_energy = eq.potential_energy = 0;
  const auto& states = tree.bodies();

  // Per body, in its own axes: its inertia about its origin, and the
  // applied-plus-inertia wrench about its origin (-m a_c with gravity inside
  // a_c, point forces, -I alpha - w x I w).
  std::vector<SpatialInertia> inertia(states.size());
  std::vector<Wrench> wrench(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::BodyState& b = states[i];
    const model::Body& body = model.bodies[b.body];
    const ex mass = vars.scalar(body.mass);
    const auto& in = body.inertia;
    const Mat3 central{vars.scalar(in[0]), vars.scalar(in[3]), vars.scalar(in[4]),
                       vars.scalar(in[3]), vars.scalar(in[1]), vars.scalar(in[5]),
                       vars.scalar(in[4]), vars.scalar(in[5]), vars.scalar(in[2])};
    const Vec3 com = vec(vars, body.com);
    const Vec3 com_velocity = named(program, b.velocity + cross(b.omega, com));
    const Vec3 com_accel =
        named(program, b.accel_rest + cross(b.alpha_rest, com) + cross(b.omega, cross(b.omega, com)));
    const Vec3 spin = named(program, mul(central, b.omega));  // I w

    Vec3 force = zero_vec() - mass * com_accel;
    Vec3 torque = zero_vec() - mul(central, b.alpha_rest) - cross(b.omega, spin);
    for (const model::PointForce& pf : model.forces) {
      if (pf.body != body.name || pf.node >= 0) continue;
      const Vec3 given = vec(vars, pf.force);
      const Vec3 f =
          pf.frame == model::ForceFrame::body ? given : named(program, mul_transposed(b.rotation, given));
      const Vec3 at = vec(vars, pf.point);
      force = force + f;
      torque = torque + cross(at - com, f);
      if (pf.frame == model::ForceFrame::world) eq.potential_energy -= dot(given, tree.world_point(b, at));
    }
    force = named(program, force);
    wrench[i] = {named(program, torque + cross(com, force)), force};

    inertia[i].mass = mass;
    inertia[i].moment = mass * com;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        inertia[i].second[3 * r + c] =
            central[3 * r + c] + mass * ((r == c ? dot(com, com) : ex(0)) - com[r] * com[c]);

    eq.kinetic_energy += (mass * dot(com_velocity, com_velocity) + dot(b.omega, spin)) / 2;
    eq.potential_energy -= mass * dot(gravity, tree.world_point(b, com));

    if (!body.flexible) continue;
    const int first = vars.elastic_first[b.body], count = vars.elastic_count[b.body];
    const std::vector<ex> eta(vars.q.begin() + first, vars.q.begin() + first + count);
    const std::vector<ex> eta_dot(vars.u.begin() + first, vars.u.begin() + first + count);
    const fem::ModelBeam& beam = flexible.at(b.body);
    FlexibleTerms terms = flexible_terms(beam, b, eta, eta_dot, program);
    for (const model::PointForce& pf : model.forces) {
      if (pf.body != body.name || pf.node < 0) continue;
      // At the deformed node p = r + T eta (+ f, the foreshortening): a force
      // and moment about the origin on the link, and (T + D)^T f on eta.
      const NodePoint node = node_point(beam, pf.node, eta, &program);
      const Vec3& at = node.position;
      const Vec3 given = vec(vars, pf.force);
      const Vec3 f =
          pf.frame == model::ForceFrame::body ? given : named(program, mul_transposed(b.rotation, given));
      terms.force = terms.force + f;
      terms.moment = terms.moment + cross(at, f);
      for (int k = 0; k < count; ++k) terms.elastic_forcing[k] += dot(node.partial[k], f);
      if (pf.frame == model::ForceFrame::world) eq.potential_energy -= dot(given, tree.world_point(b, at));
    }
    wrench[i].force = wrench[i].force + terms.force;
    wrench[i].moment = wrench[i].moment + terms.moment;
    inertia[i].mass += terms.mass;
    inertia[i].moment = inertia[i].moment + terms.first_moment;
    for (int k = 0; k < 9; ++k) inertia[i].second[k] += terms.second_moment[k];
    eq.kinetic_energy += terms.kinetic_energy;
    eq.potential_energy +=
        terms.strain_energy - dot(gravity, terms.mass * b.origin + mul(b.rotation, terms.first_moment));
    elastic.emplace(i, std::move(terms));
  }

  // Springs: their forces at the ends join the bodies' wrenches (so they
  // also enter the pull of a subtree on a beam node), their energy V.
  for (const model::Spring& spring : model.springs) {
    const SpringLoads s = spring_loads(spring, tree, vars, program);
    for (const PointLoad& load : s.loads) {
      wrench[load.state].force = wrench[load.state].force + load.force;
      wrench[load.state].moment = wrench[load.state].moment + cross(load.at, load.force);
    }
    eq.potential_energy += s.energy;
  }

  // Composite bodies and subtree wrenches, leaves first, each in its own frame.
  for (std::size_t i = states.size(); i-- > 0;) {
    SpatialInertia& c = inertia[i];
    c.mass = program.define(c.mass);
    c.moment = named(program, c.moment);
    c.second = named(program, c.second);
    wrench[i] = {named(program, wrench[i].moment), named(program, wrench[i].force)};
    const int parent = states[i].parent_state;
    if (parent < 0) continue;
    const SpatialInertia moved = to_parent(program, c, states[i].to_child, states[i].offset);
    inertia[parent].mass += moved.mass;
    inertia[parent].moment = inertia[parent].moment + moved.moment;
    for (int k = 0; k < 9; ++k) inertia[parent].second[k] += moved.second[k];
    const Wrench w = to_parent(program, wrench[i], states[i].to_child, states[i].offset);
    if (states[i].node_first >= 0)
      add_node_subtree(elastic.at(static_cast<std::size_t>(parent)), states[i], moved, w, program);
    wrench[parent].moment = wrench[parent].moment + w.moment;
    wrench[parent].force = wrench[parent].force + w.force;
  }

  // Kane's equations with the sums over bodies grouped by subtree. The
  // partial velocities of speed r (joint k, child body i) at i's origin, in
  // i's axes, are (w_r, v_r) = (a_k, 0) for a revolute and (0, a_k) for a
  // prismatic joint, and a point p of the subtree has v_r + w_r x p. So
  //   f_r  = sum_i (v_r + w_r x c_i).F_i + w_r.T_i = a_k.N_sub (revolute) or a_k.F_sub,
  //   M_rs = sum_i m_i v_r^i.v_s^i + w_r.I_i w_s = w_r.L_s + v_r.P_s,
  // where (L_s, P_s) is the momentum, about r's child origin, of the subtree
  // of joint s moving with u_s = 1 alone (r an ancestor of s or s itself).
  struct WorldAxis {
    Vec3 direction, moment;  ///< a_k and o_k x a_k in world axes
  };
  std::map<int, WorldAxis> world_axes;
  if (method == MassMatrixMethod::world_projection)
    for (const kinematics::BodyState& b : states) {
      const kinematics::JointFrame& frame = tree.joints()[b.joint];
      if (frame.speed < 0) continue;
      const Vec3 a = named(program, mul(b.rotation, frame.axis));
      world_axes[b.joint] = {a, frame.prismatic ? zero_vec() : named(program, cross(b.origin, a))};
    }
  auto project = [](const kinematics::JointFrame& frame, const Vec3& moment, const Vec3& force) {
    return frame.prismatic ? dot(frame.axis, force) : dot(frame.axis, moment);
  };
  // Row s of M from the momentum (angular, linear), about state i's origin
  // in its axes, of everything that moves with u_s = 1 alone.
  const auto spread = [&](int s, std::size_t i, Vec3 angular, Vec3 linear) {
    const kinematics::BodyState& b = states[i];
    if (method == MassMatrixMethod::world_projection) {
      // The momentum in world axes about the world origin, met by each
      // ancestor's partial velocities at the world origin: w = a, v = o x a.
      const Vec3 p_world = named(program, mul(b.rotation, linear));
      const Vec3 l_world = named(program, mul(b.rotation, angular) + cross(b.origin, p_world));
      for (int k : b.path) {
        const kinematics::JointFrame& frame = tree.joints()[k];
        const WorldAxis& axis = world_axes.at(k);
        eq.mass_matrix[s * n + frame.speed] = eq.mass_matrix[frame.speed * n + s] =
            frame.prismatic ? dot(axis.direction, p_world)
                            : dot(axis.direction, l_world) + dot(axis.moment, p_world);
      }
      return;
    }
    // Up the path: at each ancestor's frame, project on its joint.
    for (int at = static_cast<int>(i);;) {
      const kinematics::BodyState& a = states[at];
      const kinematics::JointFrame& frame = tree.joints()[a.joint];
      if (frame.speed >= 0)
        eq.mass_matrix[s * n + frame.speed] = eq.mass_matrix[frame.speed * n + s] =
            project(frame, angular, linear);
      if (a.parent_state < 0) break;
      const Wrench up = to_parent(program, {angular, linear}, a.to_child, a.offset);
      angular = up.moment;
      linear = up.force;
      for (std::size_t e = 0; e < a.node_partial_angular.size(); ++e) {
        const int r = a.node_first + static_cast<int>(e);
        eq.mass_matrix[s * n + r] = eq.mass_matrix[r * n + s] =
            dot(a.node_partial_angular[e], angular) + dot(a.node_partial_linear[e], linear);
      }
      at = a.parent_state;
    }
  };
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::BodyState& b = states[i];
    const kinematics::JointFrame& joint = tree.joints()[b.joint];
    if (joint.speed < 0) continue;
    const int s = joint.speed;
    eq.forcing[s] = project(joint, wrench[i].moment, wrench[i].force);

    const SpatialInertia& c = inertia[i];
    if (joint.prismatic)
      spread(s, i, named(program, cross(c.moment, joint.axis)), named(program, c.mass * joint.axis));
    else
      spread(s, i, named(program, mul(c.second, joint.axis)), named(program, cross(joint.axis, c.moment)));
  }
  // The elastic speeds: their own block, and their coupling with the joints on the path.
  for (const auto& [i, terms] : elastic) {
    const int body = states[i].body, first = vars.elastic_first[body], count = vars.elastic_count[body];
    for (int k = 0; k < count; ++k) {
      const int r = first + k;
      eq.forcing[r] = terms.elastic_forcing[k];
      for (int l = 0; l < count; ++l) eq.mass_matrix[r * n + first + l] = terms.elastic_mass[k * count + l];
      spread(r, i, terms.angular_momentum[k], terms.linear_momentum[k]);
    }
  }

  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const model::Joint& joint = model.joints[k];
    const int r = tree.joints()[k].speed;
    if (r < 0) continue;
    const ex stiffness = vars.scalar(joint.spring_stiffness);
    const ex stretch = vars.q[r] - vars.scalar(joint.spring_rest);
    eq.forcing[r] += -stiffness * stretch - vars.scalar(joint.damping) * vars.u[r];
    if (joint.actuated) eq.forcing[r] += vars.tau[r];
    for (const model::JointEffort& effort : model.joint_efforts)
      if (effort.joint == joint.name) eq.forcing[r] += joint_effort_value(effort, vars);
    eq.potential_energy += stiffness * stretch * stretch / 2;
    eq.coordinate_rates.push_back(vars.u[r]);
    eq.coordinate_names.push_back(joint.name);
    eq.speed_names.push_back(joint.name + "_dot");
    eq.input_names.push_back(joint.name + "_tau");
    if (!joint.is_prescribed()) {
      eq.q0.push_back(joint.q0);
      eq.u0.push_back(joint.u0);
      continue;
    }
    PrescribedSpeed prescribed;
    prescribed.speed = r;
    for (std::size_t p = 0; p < joint.prescribed.size(); ++p) {
      const model::PrescribedPiece& piece = joint.prescribed[p];
      const ex motion = vars.time_expression(piece.q, piece.where);
      prescribed.pieces.push_back({motion.diff(vars.t, 2), piece.has_until, piece.until});
      if (p == 0) {  // the initial state: in the parameters, and at their defaults
        prescribed.position0 = motion.subs(vars.t == 0);
        prescribed.speed0 = motion.diff(vars.t).subs(vars.t == 0);
        eq.q0.push_back(vars.at_defaults(motion, 0.0));
        eq.u0.push_back(vars.at_defaults(motion.diff(vars.t), 0.0));
      }
    }
    eq.prescribed.push_back(std::move(prescribed));
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].flexible) continue;
    const std::vector<std::string>& names = flexible.at(static_cast<int>(b)).reduced.names;
    for (int k = 0; k < vars.elastic_count[b]; ++k) {
      eq.coordinate_rates.push_back(vars.u[vars.elastic_first[b] + k]);
      eq.coordinate_names.push_back(model.bodies[b].name + "." + names[k]);
      eq.speed_names.push_back(model.bodies[b].name + "." + names[k] + "_dot");
      eq.q0.push_back(0.0);
      eq.u0.push_back(0.0);
    }
  }

  eq.loops = derive_loop_constraints(model, vars, program, tree, flexible);
  eq.coordinate_role.assign(eq.nq, 0);
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const int r = tree.joints()[k].speed;
    if (r >= 0)
      eq.coordinate_role[r] = model.joints[k].is_prescribed() ? 2 : model.joints[k].independent ? 1 : 0;
  }

  for (const model::Output& out : model.outputs) {
    if (out.node >= 0) {
      const int body = tree.bodies()[tree.state_of(out.body)].body;
      const int first = vars.elastic_first[body];
      const std::vector<ex> eta(vars.q.begin() + first, vars.q.begin() + first + vars.elastic_count[body]);
      const NodeOutputs node = node_outputs(model.bodies[body], flexible.at(body), out, eta, program);
      eq.outputs.insert(eq.outputs.end(), node.values.begin(), node.values.end());
      continue;
    }
    if (out.kind == model::OutputKind::point_position) {
      const int state = tree.state_of(out.body);
      Vec3 p = vec(vars, out.point);
      if (state >= 0) p = tree.world_point(tree.bodies()[state], p);
      eq.outputs.insert(eq.outputs.end(), p.begin(), p.end());
      continue;
    }
    if (out.kind == model::OutputKind::reaction) {
      for (int c = 0; c < eq.loops.size(); ++c)
        if (eq.loops.loops[c] == out.loop) {
          eq.reaction_outputs.emplace_back(static_cast<int>(eq.outputs.size()), c);
          eq.outputs.push_back(0);  // filled from lambda by the emitted code
        }
      continue;
    }
    int r = -1;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
      if (model.joints[k].name == out.joint) r = tree.joints()[k].speed;
    eq.outputs.push_back(r < 0                                             ? ex(0)
                         : out.kind == model::OutputKind::joint_coordinate ? ex(vars.q[r])
                                                                           : ex(vars.u[r]));
  }
  // The values above follow the columns the model's outputs expand into, which name them.
  for (const model::OutputColumn& column : model::output_columns(model))
    eq.output_names.push_back(column.name);
  if (eq.output_names.size() != eq.outputs.size())
    throw std::logic_error("derive_equations: the outputs' values do not match their columns");
  return eq;
}

}  // namespace kanegen::kane
