// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/equations.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "kane/articulated_body.hpp"
#include "kane/beam_node.hpp"
#include "kane/flexible_body.hpp"
#include "kane/force_elements.hpp"
#include "kane/node_outputs.hpp"
#include "kane/working_newton_euler.hpp"
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

/// What the steps that need the tree share: the inputs and the tree's kinematics.
struct Derivation {
  const model::Model& model;
  const symbolic::Variables& vars;
  Program& program;
  const FlexibleBodies& flexible;
  const kinematics::TreeKinematics& tree;
  MassMatrixMethod method;
  Vec3 gravity;
};

/// Per tree state (TreeKinematics::bodies order): the body's inertia and
/// applied-plus-inertia wrench, then, after composite_bodies, its subtree's;
/// the flexible bodies' own terms by state index.
struct BodySums {
  std::vector<SpatialInertia> inertia;
  std::vector<Wrench> wrench;
  std::vector<Wrench> applied;  ///< of `wrench`, the applied part alone (the recursion's)
  std::map<std::size_t, FlexibleTerms> elastic;
};

/// Product::bodies: each body's own inertia and wrench (before the
/// composites), and the energies of the bodies and springs.
struct BodyProducts {
  BodySums own;
  Energies energies;
};

/// Product::mass_matrix: M, the bodies' share of f, and M's pairs of world
/// axes and momenta.
struct MassProducts {
  std::vector<ex> mass_matrix, body_forcing;
  WorldMass world_mass;
};

/// Product::joint_forces: the joints' own terms, each list in the order its
/// terms join f, V and the nonconservative power.
struct JointForces {
  std::vector<std::vector<ex>> forcing;  ///< per speed
  std::vector<ex> potential, power;
};

/// The joints on nodes of flexible parents, by joint index.
std::map<int, kinematics::NodeAttachment> node_attachments(const model::Model& model,
                                                           const symbolic::Variables& vars,
                                                           const FlexibleBodies& flexible) {
  std::map<int, kinematics::NodeAttachment> attachments;
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    const model::Joint& j = model.joints[k];
    if (j.parent_node < 0) continue;
    int parent = -1;
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == j.parent) parent = static_cast<int>(b);
    if (!model::joint_type_info(j.type).on_nodes)
      throw model::ModelError(model.source_file, j.where + "/parent_node",
                              "only " + model::joint_type_list(model::JointKinds::on_nodes, "and") +
                                  " joints on beam nodes are supported",
                              "attach " + std::string(model::joint_type_info(j.type).name) + " joint '" +
                                  j.name +
                                  "' to the body frame (remove \"parent_node\"), or put a fixed joint "
                                  "and a body on the node and the slide on that body");
    const fem::ElasticModel& beam = flexible.at(parent);
    kinematics::NodeAttachment a;
    a.position = beam.point_position(j.parent_node);
    a.translation = beam.point_translation(j.parent_node);
    a.rotation = beam.point_rotation(j.parent_node);
    a.first = vars.elastic_first[parent];
    if (beam.foreshortening) {
      const auto& h = beam.foreshortening->node[j.parent_node];
      a.shortening.assign(h.begin(), h.end());
    }
    attachments.emplace(static_cast<int>(k), a);
  }
  return attachments;
}

/// State i's rigid body, in its own axes: its inertia about its origin, and
/// the applied-plus-inertia wrench about its origin (-m a_c with gravity
/// inside a_c, point forces off nodes, -I alpha - w x I w); its energies.
void add_rigid_body(Derivation& d, BodySums& sums, Energies& e, std::size_t i) {
  Program& program = d.program;
  const symbolic::Variables& vars = d.vars;
  const kinematics::BodyState& b = d.tree.bodies()[i];
  const model::Body& body = d.model.bodies[b.body];
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
  for (const model::PointForce& pf : d.model.forces) {
    if (pf.body != body.name || pf.node >= 0) continue;
    const Vec3 given = vec(vars, pf.force);
    const Vec3 f =
        pf.frame == model::ForceFrame::body ? given : named(program, mul_transposed(b.rotation, given));
    const Vec3 at = vec(vars, pf.point);
    force = force + f;
    torque = torque + cross(at - com, f);
    Wrench& applied = sums.applied[i];
    applied = {applied.moment + cross(at, f), applied.force + f};
    // A world-fixed force has a potential; one turning with the body does work.
    if (pf.frame == model::ForceFrame::world)
      e.potential -= dot(given, d.tree.world_point(b, at));
    else
      e.nonconservative_power += dot(f, b.velocity + cross(b.omega, at));
  }
  force = named(program, force);
  sums.wrench[i] = {named(program, torque + cross(com, force)), force};

  SpatialInertia& inertia = sums.inertia[i];
  inertia.mass = mass;
  inertia.moment = mass * com;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      inertia.second[3 * r + c] =
          central[3 * r + c] + mass * ((r == c ? dot(com, com) : ex(0)) - com[r] * com[c]);

  e.kinetic += (mass * dot(com_velocity, com_velocity) + dot(b.omega, spin)) / 2;
  const ex weight_potential = -mass * dot(d.gravity, d.tree.world_point(b, com));
  e.potential += weight_potential;
  e.gravity_potential += weight_potential;
}

/// State i's flexible body (after add_rigid_body for its link): the deformed
/// body's inertia and wrench join the link's, with the point forces on its
/// nodes; its elastic terms are kept for the mass matrix and the forcing.
void add_flexible_body(Derivation& d, BodySums& sums, Energies& e, std::size_t i) {
  Program& program = d.program;
  const symbolic::Variables& vars = d.vars;
  const kinematics::BodyState& b = d.tree.bodies()[i];
  const model::Body& body = d.model.bodies[b.body];
  const int first = vars.elastic_first[b.body], count = vars.elastic_count[b.body];
  const std::vector<ex> eta(vars.q.begin() + first, vars.q.begin() + first + count);
  const std::vector<ex> eta_dot(vars.u.begin() + first, vars.u.begin() + first + count);
  const fem::ElasticModel& beam = d.flexible.at(b.body);
  FlexibleTerms terms = flexible_terms(beam, b, eta, eta_dot, program);
  for (const model::PointForce& pf : d.model.forces) {
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
    if (pf.frame == model::ForceFrame::world) {
      e.potential -= dot(given, d.tree.world_point(b, at));
    } else {
      Vec3 velocity = b.velocity + cross(b.omega, at);
      for (int k = 0; k < count; ++k) velocity = velocity + eta_dot[k] * node.partial[k];
      e.nonconservative_power += dot(f, velocity);
    }
  }
  Wrench& wrench = sums.wrench[i];
  wrench.force = wrench.force + terms.force;
  wrench.moment = wrench.moment + terms.moment;
  SpatialInertia& inertia = sums.inertia[i];
  inertia.mass += terms.mass;
  inertia.moment = inertia.moment + terms.first_moment;
  for (int k = 0; k < 9; ++k) inertia.second[k] += terms.second_moment[k];
  e.kinetic += terms.kinetic_energy;
  e.nonconservative_power += terms.damping_power;
  const ex weight_potential = -dot(d.gravity, terms.mass * b.origin + mul(b.rotation, terms.first_moment));
  e.potential += terms.strain_energy + weight_potential;
  e.gravity_potential += weight_potential;
  sums.elastic.emplace(i, std::move(terms));
}

/// Springs: their forces at the ends join the bodies' wrenches (so they
/// also enter the pull of a subtree on a beam node), their energy V.
void add_springs(Derivation& d, BodySums& sums, Energies& e) {
  for (const model::Spring& spring : d.model.springs) {
    const SpringLoads s = spring_loads(spring, d.tree, d.vars, d.program);
    for (const PointLoad& load : s.loads) {
      for (Wrench* w : {&sums.wrench[load.state], &sums.applied[load.state]}) {
        w->force = w->force + load.force;
        w->moment = w->moment + cross(load.at, load.force);
      }
    }
    e.potential += s.energy;
    e.nonconservative_power += s.damping_power;
  }
}

/// Composite bodies and subtree wrenches, leaves first, each in its own
/// frame; a subtree on a beam node also joins its parent's elastic terms.
void composite_bodies(Derivation& d, BodySums& sums) {
  Program& program = d.program;
  const auto& states = d.tree.bodies();
  for (std::size_t i = states.size(); i-- > 0;) {
    SpatialInertia& c = sums.inertia[i];
    c.mass = program.define(c.mass);
    c.moment = named(program, c.moment);
    c.second = named(program, c.second);
    sums.wrench[i] = {named(program, sums.wrench[i].moment), named(program, sums.wrench[i].force)};
    const int parent = states[i].parent_state;
    if (parent < 0) continue;
    const SpatialInertia moved = to_parent(program, c, states[i].to_child, states[i].offset);
    SpatialInertia& p = sums.inertia[parent];
    p.mass += moved.mass;
    p.moment = p.moment + moved.moment;
    for (int k = 0; k < 9; ++k) p.second[k] += moved.second[k];
    const Wrench w = to_parent(program, sums.wrench[i], states[i].to_child, states[i].offset);
    if (states[i].node_first >= 0)
      add_node_subtree(sums.elastic.at(static_cast<std::size_t>(parent)), states[i], moved, w, program);
    sums.wrench[parent].moment = sums.wrench[parent].moment + w.moment;
    sums.wrench[parent].force = sums.wrench[parent].force + w.force;
  }
}

/// Speed `c` of a joint's share of a wrench, S^T w: the moment about a
/// revolute axis (a spherical joint's child axis c), the force along a prismatic one.
ex project(const kinematics::JointFrame& frame, int c, const Vec3& moment, const Vec3& force) {
  return frame.model.force_of(frame.column(c), moment, force);
}

/// Kane's equations with the sums over bodies grouped by subtree. The
/// partial velocities of speed r (joint k, child body i) at i's origin, in
/// i's axes, are (w_r, v_r) = (a_k, 0) for a revolute and (0, a_k) for a
/// prismatic joint, and a point p of the subtree has v_r + w_r x p. So
///   f_r  = sum_i (v_r + w_r x c_i).F_i + w_r.T_i = a_k.N_sub (revolute) or a_k.F_sub,
///   M_rs = sum_i m_i v_r^i.v_s^i + w_r.I_i w_s = w_r.L_s + v_r.P_s,
/// where (L_s, P_s) is the momentum, about r's child origin, of the subtree
/// of joint s moving with u_s = 1 alone (r an ancestor of s or s itself).
/// MassRows writes M's rows and columns from such momenta.
class MassRows {
 public:
  MassRows(Derivation& d, MassProducts& out) : d_(d), out_(out), n_(static_cast<int>(d.vars.u.size())) {
    if (d.method == MassMatrixMethod::world_projection) world_axes();
  }

  /// Row and column s of M from the momentum (angular, linear), about state
  /// i's origin in its axes, of everything that moves with u_s = 1 alone.
  void spread(int s, std::size_t i, const Vec3& angular, const Vec3& linear) {
    if (d_.method == MassMatrixMethod::world_projection)
      spread_in_world(s, i, angular, linear);
    else
      spread_up_the_path(s, i, angular, linear);
  }

 private:
  struct WorldAxis {
    Vec3 angular, linear;  ///< the joint's column of S at the world origin, world axes
  };

  void set(int r, int s, const ex& value) {
    out_.mass_matrix[s * n_ + r] = out_.mass_matrix[r * n_ + s] = value;
  }

  void world_axes() {
    for (const kinematics::BodyState& b : d_.tree.bodies()) {
      const kinematics::JointFrame& frame = d_.tree.joints()[b.joint];
      for (int c = 0; c < frame.speeds(); ++c) {
        const Vec3 a = named(d_.program, mul(b.rotation, frame.column(c)));
        // The column of S at the world origin: (a, o x a) for a turn, (0, a) for a slide.
        const Vec3 linear = frame.model.turns() ? named(d_.program, cross(b.origin, a)) : a;
        const WorldAxis& w = world_axes_[frame.speed + c] = {frame.model.angular_velocity(a, 1), linear};
        out_.world_mass.axis.resize(n_);
        out_.world_mass.axis[frame.speed + c] = {w.angular[0], w.angular[1], w.angular[2],
                                                 w.linear[0],  w.linear[1],  w.linear[2]};
      }
    }
  }

  /// The momentum in world axes about the world origin, met by each
  /// ancestor's partial velocities at the world origin: w = a, v = o x a.
  void spread_in_world(int s, std::size_t i, const Vec3& angular, const Vec3& linear) {
    const kinematics::BodyState& b = d_.tree.bodies()[i];
    const Vec3 p_world = named(d_.program, mul(b.rotation, linear));
    const Vec3 l_world = named(d_.program, mul(b.rotation, angular) + cross(b.origin, p_world));
    WorldMass& world = out_.world_mass;
    world.momentum.resize(n_);
    world.momentum[s] = {l_world[0], l_world[1], l_world[2], p_world[0], p_world[1], p_world[2]};
    for (int k : b.path) {
      const kinematics::JointFrame& frame = d_.tree.joints()[k];
      for (int c = 0; c < frame.speeds(); ++c) {
        const int r = frame.speed + c;
        if (k == b.joint && r > s) continue;  // a spherical joint's own later columns: their rows give these
        const WorldAxis& axis = world_axes_.at(r);
        world.pairs.emplace_back(r, s);
        set(r, s, dot(axis.angular, l_world) + dot(axis.linear, p_world));
      }
    }
  }

  /// Up the path: at each ancestor's frame, project on its joint and on the
  /// elastic speeds of a beam node it hangs on.
  void spread_up_the_path(int s, std::size_t i, Vec3 angular, Vec3 linear) {
    const auto& states = d_.tree.bodies();
    for (int at = static_cast<int>(i);;) {
      const kinematics::BodyState& a = states[at];
      const kinematics::JointFrame& frame = d_.tree.joints()[a.joint];
      for (int c = 0; c < frame.speeds(); ++c)
        if (at != static_cast<int>(i) || frame.speed + c <= s)  // own later columns: their rows
          set(frame.speed + c, s, project(frame, c, angular, linear));
      if (a.parent_state < 0) break;
      const Wrench up = to_parent(d_.program, {angular, linear}, a.to_child, a.offset);
      angular = up.moment;
      linear = up.force;
      for (std::size_t e = 0; e < a.node_partial_angular.size(); ++e)
        set(a.node_first + static_cast<int>(e), s,
            dot(a.node_partial_angular[e], angular) + dot(a.node_partial_linear[e], linear));
      at = a.parent_state;
    }
  }

  Derivation& d_;
  MassProducts& out_;
  const int n_;
  std::map<int, WorldAxis> world_axes_;  ///< by speed
};

/// The joint speeds' rows: the forcing from the subtree's wrench, M from the
/// momentum of the subtree turning (sliding) with u_s = 1.
void joint_rows(Derivation& d, const BodySums& sums, MassRows& rows, MassProducts& out) {
  const auto& states = d.tree.bodies();
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::JointFrame& joint = d.tree.joints()[states[i].joint];
    for (int column = 0; column < joint.speeds(); ++column) {
      const int s = joint.speed + column;
      out.body_forcing[s] = project(joint, column, sums.wrench[i].moment, sums.wrench[i].force);

      // The momentum of the subtree with u_s = 1. Linear part named first: the
      // order GCC gave when both were arguments of one call, now fixed.
      const SpatialInertia& c = sums.inertia[i];
      const auto [unit_angular, unit_linear] =
          joint.model.unit_momentum(c.mass, c.moment, c.second, joint.column(column));
      const Vec3 linear = named(d.program, unit_linear);
      const Vec3 angular = named(d.program, unit_angular);
      rows.spread(s, i, angular, linear);
    }
  }
}

/// The elastic speeds' rows: their own block, and their coupling with the joints on the path.
void elastic_rows(Derivation& d, const BodySums& sums, MassRows& rows, MassProducts& out) {
  const int n = static_cast<int>(d.vars.u.size());
  for (const auto& [i, terms] : sums.elastic) {
    const int body = d.tree.bodies()[i].body;
    const int first = d.vars.elastic_first[body], count = d.vars.elastic_count[body];
    for (int k = 0; k < count; ++k) {
      const int r = first + k;
      out.body_forcing[r] = terms.elastic_forcing[k];
      for (int l = 0; l < count; ++l) out.mass_matrix[r * n + first + l] = terms.elastic_mass[k * count + l];
      rows.spread(r, i, terms.angular_momentum[k], terms.linear_momentum[k]);
    }
  }
}

/// Outward over a rigid tree, the motion that the joint rates alone give
/// (rates: u for velocities, u_dot for accelerations), in each body's axes:
///   w_i = E_i w_p + a_k rate_k (revolute),
///   v_i = E_i (v_p + w_p x r_i) + a_k rate_k (prismatic).
struct RateMotion {
  std::vector<Vec3> angular, linear;
};

RateMotion motion_of_rates(Derivation& d, const std::vector<GiNaC::symbol>& rates) {
  const auto& states = d.tree.bodies();
  RateMotion out{std::vector<Vec3>(states.size()), std::vector<Vec3>(states.size())};
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::BodyState& b = states[i];
    const kinematics::JointFrame& joint = d.tree.joints()[b.joint];
    Vec3 angular = zero_vec(), linear = zero_vec();
    if (b.parent_state >= 0) {
      const Vec3& parent_angular = out.angular[b.parent_state];
      angular = mul(b.to_child, parent_angular);
      linear = mul(b.to_child, out.linear[b.parent_state] + cross(parent_angular, b.offset));
    }
    for (int c = 0; c < joint.speeds(); ++c) {
      const ex rate = rates[joint.speed + c];
      Vec3& moved = joint.model.part(angular, linear);  // + S rate
      moved = moved + rate * joint.column(c);
    }
    out.angular[i] = named(d.program, angular);
    out.linear[i] = named(d.program, linear);
  }
  return out;
}

/// A body's momentum about its origin for the motion (w, v): (K w + h x v, m v + w x h).
Wrench momentum_of(const SpatialInertia& m, const Vec3& angular, const Vec3& linear) {
  return {mul(m.second, angular) + cross(m.moment, linear), m.mass * linear + cross(angular, m.moment)};
}

/// Inward: each body's wrench named and added, in its parent's axes, to its parent's.
void sum_into_parents(Derivation& d, std::vector<Wrench>& sums) {
  const auto& states = d.tree.bodies();
  for (std::size_t i = sums.size(); i-- > 0;) {
    sums[i] = {named(d.program, sums[i].moment), named(d.program, sums[i].force)};
    const int parent = states[i].parent_state;
    if (parent < 0) continue;
    const Wrench up = to_parent(d.program, sums[i], states[i].to_child, states[i].offset);
    sums[parent].moment = sums[parent].moment + up.moment;
    sums[parent].force = sums[parent].force + up.force;
  }
}

std::vector<ex> as_ex(const std::vector<GiNaC::symbol>& symbols) { return {symbols.begin(), symbols.end()}; }

/// The recursions' view of each body (TreeKinematics::bodies order): its own
/// inertia, its applied-plus-inertia wrench and, apart, the applied part
/// alone; a flexible body's floating-frame and elastic terms.
std::vector<TreeBody> tree_bodies(const Derivation& d, const BodySums& own) {
  std::vector<TreeBody> bodies;
  for (std::size_t i = 0; i < own.inertia.size(); ++i) {
    TreeBody& b = bodies.emplace_back();
    b.mass = own.inertia[i].mass;
    b.moment = own.inertia[i].moment;
    b.second = own.inertia[i].second;
    b.wrench_moment = own.wrench[i].moment;
    b.wrench_force = own.wrench[i].force;
    b.applied_moment = own.applied[i].moment;
    b.applied_force = own.applied[i].force;
    const auto elastic = own.elastic.find(i);
    if (elastic == own.elastic.end()) continue;
    b.elastic_first = d.vars.elastic_first[d.tree.bodies()[i].body];
    b.elastic_angular = elastic->second.angular_momentum;
    b.elastic_linear = elastic->second.linear_momentum;
    b.elastic_mass = elastic->second.elastic_mass;
    b.elastic_forcing = elastic->second.elastic_forcing;
  }
  return bodies;
}

/// Rigid trees: M u_dot - f (u_dot = Variables::udot, without the joints'
/// own forces) and the gravity g(q) = dV_gravity/dq by Newton and Euler's
/// recursion, without M, in the working frames (kane/working_newton_euler.*).
InverseDynamics newton_euler(Derivation& d, const BodySums& own) {
  const NewtonEuler ne = working_newton_euler(d.tree, tree_bodies(d, own), as_ex(d.vars.u),
                                              as_ex(d.vars.udot), d.gravity, d.program);
  return {ne.inertial, ne.gravity};
}

/// Rigid trees: the generalized momentum h = M u by Newton and Euler's recursion in body frames
/// with velocities for accelerations. Outward, each body's angular velocity
/// and its origin's velocity w_i = E_i w_p + a_k u_k, v_i = E_i (v_p + w_p x r_i)
/// (+ a_k u_k if prismatic); its momentum about its origin (K w + h x v, m v + w x h);
/// inward, the subtree sums projected on each joint: O(n), where M u is O(n^2).
std::vector<ex> momentum_recursion(Derivation& d, const BodySums& own) {
  const auto& states = d.tree.bodies();
  const std::size_t count = states.size();
  const RateMotion motion = motion_of_rates(d, d.vars.u);
  std::vector<Wrench> momentum(count);  // (angular about the origin, linear)
  for (std::size_t i = 0; i < count; ++i)
    momentum[i] = momentum_of(own.inertia[i], motion.angular[i], motion.linear[i]);
  sum_into_parents(d, momentum);
  std::vector<ex> generalized(d.vars.u.size(), 0);
  for (std::size_t i = 0; i < count; ++i) {
    const kinematics::JointFrame& joint = d.tree.joints()[states[i].joint];
    for (int c = 0; c < joint.speeds(); ++c)
      generalized[joint.speed + c] = project(joint, c, momentum[i].moment, momentum[i].force);
  }
  return generalized;
}

/// Why the articulated-body recursion does not apply, or "" if it does:
/// it covers open trees, rigid or flexible, whose every speed is solved for.
std::string recursive_unavailable(const Derivation& d, bool loops, bool prescribed) {
  if (loops) return "it has closed loops (their constraint forces need the saddle-point solve)";
  if (prescribed) return "it has prescribed motions (their accelerations are given, not solved for)";
  if (!d.vars.quaternion_w.empty())
    return "it has a spherical or free joint (the recursion solves joints of one speed)";
  return "";
}

/// What the articulated-body recursion reads besides the tree: the bodies'
/// own inertias and wrenches (before the composites), f and its bodies'
/// share (the joints' own forces are the difference), the coordinates' names.
struct RecursionInputs {
  const BodySums& own;
  const std::vector<ex>& forcing;
  const std::vector<ex>& body_forcing;
  const std::vector<std::string>& coordinate_names;
};

/// u_dot by the articulated-body recursion over the bodies' own inertias and
/// wrenches; the joints' own forces are f less the bodies' share.
Recursion recursive_dynamics(Derivation& d, const RecursionInputs& in) {
  Recursion out;
  const std::vector<TreeBody> bodies = tree_bodies(d, in.own);
  const std::size_t nu = d.vars.u.size();
  std::vector<ex> joint_forces(nu);
  for (std::size_t r = 0; r < nu; ++r) joint_forces[r] = in.forcing[r] - in.body_forcing[r];
  RecursiveDynamics r = articulated_body_dynamics(d.tree, bodies, joint_forces, as_ex(d.vars.u), d.program);
  if (r.zero_pivot >= 0) {
    out.unavailable = "elastic coordinate '" + in.coordinate_names[r.zero_pivot] +
                      "' moves no inertia in any state (the recursion divides by it)";
    for (std::size_t k = 0; k < d.model.joints.size(); ++k)
      if (d.tree.joints()[k].speed == r.zero_pivot) {
        out.unavailable = "joint '" + d.model.joints[k].name +
                          "' moves no inertia about or along its axis in any state (the "
                          "recursion divides by it)";
        out.unavailable_place = d.model.joints[k].where;
      }
    return out;
  }
  out.accelerations = std::move(r.accelerations);
  out.pivots = std::move(r.pivots);
  out.pivot_order = std::move(r.pivot_order);
  return out;
}

/// What the steps that need no kinematics read.
struct Inputs {
  const model::Model& model;
  const symbolic::Variables& vars;
  const FlexibleBodies& flexible;
};

/// The joint's own forces on its speed r: spring, damper, actuator, efforts; the spring's energy.
void add_joint_forces(const Inputs& d, JointForces& out, const model::Joint& joint, int r) {
  const symbolic::Variables& vars = d.vars;
  const ex stiffness = vars.scalar(joint.spring_stiffness);
  const ex stretch = vars.q[r] - vars.scalar(joint.spring_rest);
  std::vector<ex>& forcing = out.forcing[r];
  forcing.push_back(-stiffness * stretch - vars.scalar(joint.damping) * vars.u[r]);
  ex nonconservative = -vars.scalar(joint.damping) * vars.u[r];
  if (joint.actuated) {
    forcing.push_back(vars.tau[r]);
    nonconservative += vars.tau[r];
  }
  for (const model::JointEffort& effort : d.model.joint_efforts)
    if (effort.joint == joint.name) {
      const ex value = joint_effort_value(effort, vars);
      forcing.push_back(value);
      nonconservative += value;
    }
  out.potential.push_back(stiffness * stretch * stretch / 2);
  out.power.push_back(nonconservative * vars.u[r]);
}

/// Every joint's own forces, joint by joint, speed by speed.
JointForces joint_forces(const Inputs& d) {
  JointForces out;
  out.forcing.resize(d.vars.u.size());
  for (std::size_t k = 0; k < d.model.joints.size(); ++k) {
    const int r = d.vars.first_speed[k];
    if (r < 0) continue;
    const int speeds = model::joint_type_info(d.model.joints[k].type).speeds;
    for (int c = 0; c < speeds; ++c) add_joint_forces(d, out, d.model.joints[k], r + c);
  }
  return out;
}

/// A prescribed joint's accelerations piece by piece, and the initial state its motion gives.
void add_prescribed_speed(const Inputs& d, Coordinates& out, const model::Joint& joint, int r) {
  const symbolic::Variables& vars = d.vars;
  PrescribedSpeed prescribed;
  prescribed.speed = r;
  for (std::size_t p = 0; p < joint.prescribed.size(); ++p) {
    const model::PrescribedPiece& piece = joint.prescribed[p];
    const ex motion = vars.time_expression(piece.q, piece.where);
    prescribed.pieces.push_back({motion.diff(vars.t, 2), piece.has_until, piece.until});
    if (p == 0) {  // the initial state: in the parameters, and at their defaults
      prescribed.position0 = motion.subs(vars.t == 0);
      prescribed.speed0 = motion.diff(vars.t).subs(vars.t == 0);
      out.q0.push_back(vars.at_defaults(motion, 0.0));
      out.u0.push_back(vars.at_defaults(motion.diff(vars.t), 0.0));
    }
  }
  out.prescribed.push_back(std::move(prescribed));
}
/// The bodies in `below` and every body below them in the tree, in model order.
std::vector<std::string> subtree_bodies(const model::Model& model, std::set<std::string> below) {
  for (bool grew = true; grew;) {
    grew = false;
    for (const model::Joint& joint : model.joints)
      if (below.count(joint.parent) && below.insert(joint.child).second) grew = true;
  }
  std::vector<std::string> names;
  for (const model::Body& body : model.bodies)
    if (below.count(body.name)) names.push_back(body.name);
  return names;
}

/// What the elastic coordinates of a flexible body move: the body and what
/// hangs on its nodes (a joint on the body's own frame stays with the frame).
std::vector<std::string> elastically_moved_bodies(const model::Model& model, const std::string& body) {
  std::set<std::string> on_nodes;
  for (const model::Joint& joint : model.joints)
    if (joint.parent == body && joint.parent_node != -1) on_nodes.insert(joint.child);
  const std::vector<std::string> below = subtree_bodies(model, on_nodes);
  std::set<std::string> moved(below.begin(), below.end());
  moved.insert(body);
  std::vector<std::string> names;
  for (const model::Body& b : model.bodies)
    if (moved.count(b.name)) names.push_back(b.name);
  return names;
}

/// A spherical joint's speeds: its quaternion's x, y, z (at its speeds'
/// indices) with q_dot = 1/2 q (0, u), the inputs (moments about the child
/// axes), names and initial state; the quaternion's w comes after every
/// other coordinate (quaternion_scalars).
void spherical_coordinates(const Inputs& d, Coordinates& out, const model::Joint& joint, int r, int w_index) {
  const symbolic::Variables& vars = d.vars;
  const Vec3 v{vars.q[r], vars.q[r + 1], vars.q[r + 2]}, u{vars.u[r], vars.u[r + 1], vars.u[r + 2]};
  const Vec3 rate = GiNaC::ex(1) / 2 * (vars.q[w_index] * u + cross(v, u));
  // A model file gives the quaternion as w, x, y, z; none means no turn.
  const std::vector<double> q0 = joint.step_q0.empty() ? std::vector<double>{1, 0, 0, 0} : joint.step_q0;
  for (int c = 0; c < 3; ++c) {
    const std::string axis(1, "xyz"[c]);
    out.rates.push_back(rate[c]);
    out.coordinate_names.push_back(joint.name + "_q" + axis);
    out.coordinate_joints.push_back(joint.name);
    out.moved_bodies.push_back(subtree_bodies(d.model, {joint.child}));
    out.speed_names.push_back(joint.name + "_w" + axis);
    out.input_names.push_back(joint.name + "_m" + axis);
    out.q0.push_back(q0[1 + c]);
    out.u0.push_back(joint.step_u0.empty() ? 0.0 : joint.step_u0[c]);
  }
}

/// The spherical joints' quaternion w, after every coordinate that has a
/// speed: w_dot = -1/2 (x, y, z) . u.
void quaternion_scalars(const Inputs& d, Coordinates& out) {
  for (const auto& [k, w_index] : d.vars.quaternion_w) {
    const model::Joint& joint = d.model.joints[k];
    const int r = d.vars.first_speed[k];
    const symbolic::Variables& vars = d.vars;
    if (static_cast<int>(out.rates.size()) != w_index)
      throw std::logic_error("kane::DerivationContext: a quaternion's w out of its place in q");
    out.rates.push_back(
        -(vars.q[r] * vars.u[r] + vars.q[r + 1] * vars.u[r + 1] + vars.q[r + 2] * vars.u[r + 2]) / 2);
    out.coordinate_names.push_back(joint.name + "_qw");
    out.coordinate_joints.push_back(joint.name);
    out.moved_bodies.push_back(subtree_bodies(d.model, {joint.child}));
    out.q0.push_back(joint.step_q0.empty() ? 1.0 : joint.step_q0[0]);
  }
}

/// The joint coordinates: rates, names and initial state.
void joint_coordinates(const Inputs& d, Coordinates& out) {
  for (std::size_t k = 0; k < d.model.joints.size(); ++k) {
    const model::Joint& joint = d.model.joints[k];
    const int r = d.vars.first_speed[k];
    if (r < 0) continue;
    const auto w = d.vars.quaternion_w.find(static_cast<int>(k));
    if (w != d.vars.quaternion_w.end()) {
      spherical_coordinates(d, out, joint, r, w->second);
      continue;
    }
    out.rates.push_back(d.vars.u[r]);
    out.coordinate_names.push_back(joint.name);
    out.coordinate_joints.push_back(joint.name);
    out.moved_bodies.push_back(subtree_bodies(d.model, {joint.child}));
    out.speed_names.push_back(joint.name + "_dot");
    out.input_names.push_back(joint.name + "_tau");
    if (joint.is_prescribed()) {
      add_prescribed_speed(d, out, joint, r);
    } else {
      out.q0.push_back(joint.q0);
      out.u0.push_back(joint.u0);
    }
  }
}

/// The model's initial value of the elastic coordinate `name`: given, or 0.
double elastic_initial(const std::map<std::string, double>& given, const std::string& name) {
  const auto value = given.find(name);
  return value == given.end() ? 0.0 : value->second;
}

/// check_model has checked the given names against model::elastic_coordinate_names;
/// this guards its agreement with the finite-element layer's names.
void require_known_initial_names(const model::Body& body, const std::vector<std::string>& names) {
  for (const auto* given : {&body.elastic.initial_q, &body.elastic.initial_u})
    for (const auto& entry : *given)
      if (std::find(names.begin(), names.end(), entry.first) == names.end())
        throw std::logic_error("internal error: elastic coordinate '" + entry.first + "' of body '" +
                               body.name +
                               "' passed the model check but the finite-element body has no such coordinate");
}

/// The elastic coordinates, after the joints': rates, names, the initial
/// state (the model's values, else rest).
void elastic_coordinates(const Inputs& d, Coordinates& out) {
  const model::Model& model = d.model;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].flexible) continue;
    const model::ElasticPart& beam = model.bodies[b].elastic;
    const std::vector<std::string>& names = d.flexible.at(static_cast<int>(b)).reduced.names;
    require_known_initial_names(model.bodies[b], names);
    for (int k = 0; k < d.vars.elastic_count[b]; ++k) {
      out.rates.push_back(d.vars.u[d.vars.elastic_first[b] + k]);
      out.coordinate_names.push_back(model.bodies[b].name + "." + names[k]);
      out.coordinate_joints.push_back("");
      out.moved_bodies.push_back(elastically_moved_bodies(model, model.bodies[b].name));
      out.speed_names.push_back(model.bodies[b].name + "." + names[k] + "_dot");
      out.q0.push_back(elastic_initial(beam.initial_q, names[k]));
      out.u0.push_back(elastic_initial(beam.initial_u, names[k]));
    }
  }
}

/// Per coordinate: free, independent (kept by assembly) or prescribed.
void coordinate_roles(const Inputs& d, Coordinates& out) {
  out.roles.assign(d.vars.q.size(), 0);
  for (std::size_t k = 0; k < d.model.joints.size(); ++k) {
    const model::Joint& joint = d.model.joints[k];
    const int speeds = model::joint_type_info(joint.type).speeds;
    for (int c = 0; c < speeds; ++c)
      out.roles[d.vars.first_speed[k] + c] = joint.is_prescribed() ? 2 : joint.independent ? 1 : 0;
  }
}

/// Product::coordinates.
Coordinates coordinates_of(const Inputs& d) {
  Coordinates out;
  joint_coordinates(d, out);
  elastic_coordinates(d, out);
  quaternion_scalars(d, out);
  coordinate_roles(d, out);
  return out;
}

/// The named outputs' values, each expanded into its columns; `loops`
/// gives the constraint rows where an output is a loop's reaction.
template <class Loops>
Outputs expand_outputs(Derivation& d, Loops loops) {
  const model::Model& model = d.model;
  const symbolic::Variables& vars = d.vars;
  const kinematics::TreeKinematics& tree = d.tree;
  Outputs eq;
  for (const model::Output& out : model.outputs) {
    if (out.node >= 0) {
      const int body = tree.bodies()[tree.state_of(out.body)].body;
      const int first = vars.elastic_first[body];
      const std::vector<ex> eta(vars.q.begin() + first, vars.q.begin() + first + vars.elastic_count[body]);
      const NodeOutputs node = node_outputs(model.bodies[body], d.flexible.at(body), out, eta, d.program);
      eq.values.insert(eq.values.end(), node.values.begin(), node.values.end());
      continue;
    }
    if (out.kind == model::OutputKind::point_position) {
      const int state = tree.state_of(out.body);
      Vec3 p = vec(vars, out.point);
      if (state >= 0) p = tree.world_point(tree.bodies()[state], p);
      eq.values.insert(eq.values.end(), p.begin(), p.end());
      continue;
    }
    if (out.kind == model::OutputKind::reaction) {
      const LoopConstraints& constraints = loops();
      for (int c = 0; c < constraints.size(); ++c)
        if (constraints.loops[c] == out.loop) {
          eq.reactions.emplace_back(static_cast<int>(eq.values.size()), c);
          eq.values.push_back(0);  // filled from lambda by the emitted code
        }
      continue;
    }
    int r = -1;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
      if (model.joints[k].name == out.joint) r = tree.joints()[k].speed;
    eq.values.push_back(r < 0                                             ? ex(0)
                        : out.kind == model::OutputKind::joint_coordinate ? ex(vars.q[r])
                                                                          : ex(vars.u[r]));
  }
  // The values above follow the columns the model's outputs expand into, which name them.
  for (const model::OutputColumn& column : model::output_columns(model)) eq.names.push_back(column.name);
  if (eq.names.size() != eq.values.size())
    throw std::logic_error("kane::DerivationContext: the outputs' values do not match their columns");
  return eq;
}

}  // namespace

/// The inputs, and each product once derived.
struct DerivationContext::State {
  State(const model::Model& m, const symbolic::Variables& v, Program& p, const FlexibleBodies& f,
        MassMatrixMethod how)
      : model(m), vars(v), program(p), flexible(f), method(how), gravity(vec(v, m.gravity)) {}

  const model::Model& model;
  const symbolic::Variables& vars;
  Program& program;
  const FlexibleBodies& flexible;
  MassMatrixMethod method;
  Vec3 gravity;
  std::array<int, static_cast<std::size_t>(Product::count)> derived{};
  std::map<int, kinematics::NodeAttachment> attachments;
  std::optional<kinematics::TreeKinematics> tree;
  std::optional<BodyProducts> bodies;
  std::optional<MassProducts> mass;
  std::optional<Coordinates> coordinates;
  std::optional<JointForces> joint_forces;
  std::optional<std::vector<ex>> forcing;
  std::optional<Energies> energies;
  std::optional<LoopConstraints> loops;
  std::optional<InverseDynamics> inverse;
  std::optional<std::vector<ex>> momentum;
  std::optional<Recursion> recursion;
  std::optional<Outputs> outputs;

  /// The product in `slot`, derived by `derive` on the first request.
  template <class T, class Derive>
  const T& memo(std::optional<T>& slot, Product product, Derive derive) {
    if (!slot) {
      slot.emplace(derive());
      ++derived[static_cast<std::size_t>(product)];
    }
    return *slot;
  }

  Inputs inputs() const { return {model, vars, flexible}; }

  /// The steps' view, the tree's kinematics derived on first use.
  Derivation derivation() {
    if (!tree) {
      attachments = node_attachments(model, vars, flexible);
      // The world-axes sum of M does not know the nodes' partial velocities.
      if (!attachments.empty()) method = MassMatrixMethod::body_frames;
      // The ground accelerates at -g: every rest acceleration then carries gravity.
      tree.emplace(model, vars, program, zero_vec() - gravity, attachments);
      ++derived[static_cast<std::size_t>(Product::kinematics)];
    }
    return {model, vars, program, flexible, *tree, method, gravity};
  }
};

namespace {

using State = DerivationContext::State;

/// Product::bodies: each body's own inertia and wrench, springs included;
/// their energies.
const BodyProducts& bodies(State& s) {
  return s.memo(s.bodies, Product::bodies, [&s] {
    Derivation d = s.derivation();
    const std::size_t count = d.tree.bodies().size();
    BodyProducts out{
        {std::vector<SpatialInertia>(count), std::vector<Wrench>(count), std::vector<Wrench>(count), {}}, {}};
    for (std::size_t i = 0; i < count; ++i) {
      add_rigid_body(d, out.own, out.energies, i);
      if (d.model.bodies[d.tree.bodies()[i].body].flexible) add_flexible_body(d, out.own, out.energies, i);
    }
    add_springs(d, out.own, out.energies);
    return out;
  });
}

/// Product::mass_matrix: the composite bodies and subtree wrenches, then M's
/// rows and the bodies' share of f.
const MassProducts& mass(State& s) {
  return s.memo(s.mass, Product::mass_matrix, [&s] {
    BodySums sums = bodies(s).own;
    Derivation d = s.derivation();
    const std::size_t nu = s.vars.u.size();
    MassProducts out{std::vector<ex>(nu * nu, 0), std::vector<ex>(nu, 0), {}};
    composite_bodies(d, sums);
    MassRows rows(d, out);
    joint_rows(d, sums, rows, out);
    elastic_rows(d, sums, rows, out);
    // The elastic blocks are not pairs of axes and momenta.
    if (!s.flexible.empty()) out.world_mass = {};
    return out;
  });
}

const JointForces& joint_forces(State& s) {
  return s.memo(s.joint_forces, Product::joint_forces, [&s] { return joint_forces(s.inputs()); });
}

const std::vector<ex>& forcing(State& s) {
  return s.memo(s.forcing, Product::forcing, [&s] {
    std::vector<ex> f = mass(s).body_forcing;
    const JointForces& joints = joint_forces(s);
    for (std::size_t r = 0; r < f.size(); ++r)
      for (const ex& term : joints.forcing[r]) f[r] += term;
    return f;
  });
}

const Coordinates& coordinates(State& s) {
  return s.memo(s.coordinates, Product::coordinates, [&s] { return coordinates_of(s.inputs()); });
}

const LoopConstraints& loops(State& s) {
  return s.memo(s.loops, Product::loops, [&s] {
    Derivation d = s.derivation();
    return derive_loop_constraints(s.model, s.vars, s.program, d.tree, s.flexible);
  });
}

/// T and V of the bodies, springs and joints; the nonconservative power.
const Energies& energies(State& s) {
  return s.memo(s.energies, Product::energies, [&s] {
    Energies e = bodies(s).energies;
    const JointForces& joints = joint_forces(s);
    for (const ex& term : joints.potential) e.potential += term;
    for (const ex& term : joints.power) e.nonconservative_power += term;
    GiNaC::exmap no_inputs;
    for (const GiNaC::symbol& tau : s.vars.tau) no_inputs[tau] = 0;
    e.nonconservative =
        !e.nonconservative_power.subs(no_inputs).is_zero() || !coordinates(s).prescribed.empty();
    return e;
  });
}

/// Outlives every context that keeps a reference to it.
const FlexibleBodies& no_flexible_bodies() {
  static const FlexibleBodies none;
  return none;
}

}  // namespace

DerivationContext::DerivationContext(const model::Model& model, const symbolic::Variables& vars,
                                     symbolic::Program& program, MassMatrixMethod method)
    : DerivationContext(model, vars, program, method, no_flexible_bodies()) {}

DerivationContext::DerivationContext(const model::Model& model, const symbolic::Variables& vars,
                                     symbolic::Program& program, MassMatrixMethod method,
                                     const FlexibleBodies& flexible)
    : state_(std::make_unique<State>(model, vars, program, flexible, method)) {}

DerivationContext::~DerivationContext() = default;

const model::Model& DerivationContext::model() const { return state_->model; }
const symbolic::Variables& DerivationContext::variables() const { return state_->vars; }
int DerivationContext::nq() const { return static_cast<int>(state_->vars.q.size()); }
int DerivationContext::nu() const { return static_cast<int>(state_->vars.u.size()); }
bool DerivationContext::has_loops() const { return !state_->model.loops.empty(); }

const Coordinates& DerivationContext::coordinates() { return kane::coordinates(*state_); }
const std::vector<ex>& DerivationContext::mass_matrix() { return mass(*state_).mass_matrix; }
const WorldMass& DerivationContext::world_mass() { return mass(*state_).world_mass; }
const std::vector<ex>& DerivationContext::forcing() { return kane::forcing(*state_); }
const std::vector<ex>& DerivationContext::body_forcing() { return mass(*state_).body_forcing; }
const Energies& DerivationContext::energies() { return kane::energies(*state_); }
const LoopConstraints& DerivationContext::loops() { return kane::loops(*state_); }

const InverseDynamics& DerivationContext::inverse_dynamics() {
  State& s = *state_;
  return s.memo(s.inverse, Product::inverse_dynamics, [this, &s] {
    InverseDynamics out;
    if (!s.flexible.empty()) return out;
    Derivation d = s.derivation();
    out = newton_euler(d, bodies(s).own);
    // The joints' own forces (springs, dampers, inputs, efforts) join f after the bodies'.
    const std::vector<ex>& f = forcing();
    const std::vector<ex>& body = body_forcing();
    for (std::size_t r = 0; r < out.inertial.size(); ++r) out.inertial[r] -= f[r] - body[r];
    return out;
  });
}

const std::vector<ex>& DerivationContext::generalized_momentum() {
  State& s = *state_;
  return s.memo(s.momentum, Product::generalized_momentum, [&s] {
    if (!s.flexible.empty()) return std::vector<ex>();
    Derivation d = s.derivation();
    return momentum_recursion(d, bodies(s).own);
  });
}

const Recursion& DerivationContext::recursion() {
  State& s = *state_;
  return s.memo(s.recursion, Product::recursion, [this, &s] {
    Derivation d = s.derivation();
    Recursion out;
    out.unavailable = recursive_unavailable(d, has_loops(), !coordinates().prescribed.empty());
    if (!out.unavailable.empty()) return out;
    return recursive_dynamics(d, {bodies(s).own, forcing(), body_forcing(), coordinates().coordinate_names});
  });
}

const Outputs& DerivationContext::outputs() {
  State& s = *state_;
  return s.memo(s.outputs, Product::outputs, [this, &s] {
    Derivation d = s.derivation();
    return expand_outputs(d, [this]() -> const LoopConstraints& { return loops(); });
  });
}

int DerivationContext::derivations(Product product) const {
  return state_->derived[static_cast<std::size_t>(product)];
}

}  // namespace kanegen::kane
