#include "kane/equations.hpp"

#include "kinematics/tree_kinematics.hpp"
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

/// World-axes inertia R I R^T, with its six distinct entries named.
Mat3 world_inertia(symbolic::Program& program, const Mat3& rotation, const Mat3& local) {
  Mat3 rt;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt[3 * i + j] = rotation[3 * j + i];
  const Mat3 full = mul(rotation, mul(local, rt));
  Mat3 world;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) world[3 * i + j] = world[3 * j + i] = program.define(full[3 * i + j]);
  return world;
}

/// Mass, first moment m c and second moment K = I + m (|c|^2 1 - c c^T) of a
/// set of bodies about the world origin: enough to give the momentum of the
/// set moving as one rigid body.
struct SpatialInertia {
  ex mass = 0;
  Vec3 moment = zero_vec();
  Mat3 second = Mat3{0, 0, 0, 0, 0, 0, 0, 0, 0};
};

/// Resultant force and moment about the world origin.
struct Wrench {
  Vec3 moment = zero_vec();
  Vec3 force = zero_vec();
};

}  // namespace

Equations derive_equations(const model::Model& model, const symbolic::Variables& vars, symbolic::Program& program) {
  const kinematics::TreeKinematics tree(model, vars, program);
  Equations eq;
  eq.nq = eq.nu = static_cast<int>(vars.q.size());
  const int n = eq.nu;
  eq.mass_matrix.assign(n * n, 0);
  eq.forcing.assign(n, 0);
  eq.kinetic_energy = eq.potential_energy = 0;
  const Vec3 gravity = vec(vars, model.gravity);
  const auto& states = tree.bodies();

  // Per body: its inertia about the world origin, and the applied-plus-inertia
  // wrench (gravity, point forces, -m a_c, -I alpha - w x I w) about the origin.
  std::vector<SpatialInertia> inertia(states.size());
  std::vector<Wrench> wrench(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::BodyState& b = states[i];
    const model::Body& body = model.bodies[b.body];
    const ex mass = vars.scalar(body.mass);
    const auto& in = body.inertia;
    const Mat3 local{vars.scalar(in[0]), vars.scalar(in[3]), vars.scalar(in[4]),
                     vars.scalar(in[3]), vars.scalar(in[1]), vars.scalar(in[5]),
                     vars.scalar(in[4]), vars.scalar(in[5]), vars.scalar(in[2])};
    const Mat3 central = world_inertia(program, b.rotation, local);
    const Vec3 com = tree.point(b, vec(vars, body.com));
    const Vec3 com_velocity = tree.point_velocity(b, com);
    const Vec3 com_accel = tree.point_accel_rest(b, com);
    const Vec3 spin = named(program, mul(central, b.omega));  // I w

    Vec3 force = mass * (gravity - com_accel);
    Vec3 torque = zero_vec() - mul(central, b.alpha_rest) - cross(b.omega, spin);
    for (const model::PointForce& pf : model.forces) {
      if (pf.body != body.name) continue;
      const Vec3 given = vec(vars, pf.force);
      const Vec3 f = pf.frame == model::ForceFrame::world ? given : mul(b.rotation, given);
      const Vec3 at = tree.point(b, vec(vars, pf.point));
      force = force + f;
      torque = torque + cross(at - com, f);
      if (pf.frame == model::ForceFrame::world) eq.potential_energy -= dot(f, at);
    }
    force = named(program, force);
    wrench[i] = {named(program, torque + cross(com, force)), force};

    const Vec3 h = named(program, mass * com);
    inertia[i].mass = mass;
    inertia[i].moment = h;
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c)
        inertia[i].second[3 * r + c] = inertia[i].second[3 * c + r] =
            program.define(central[3 * r + c] + (r == c ? dot(com, h) : ex(0)) - com[r] * h[c]);

    eq.kinetic_energy += (mass * dot(com_velocity, com_velocity) + dot(b.omega, spin)) / 2;
    eq.potential_energy -= mass * dot(gravity, com);
  }

  // Composite bodies: each subtree's inertia and wrench, leaves first.
  for (std::size_t i = states.size(); i-- > 0;) {
    SpatialInertia& c = inertia[i];
    c.mass = program.define(c.mass);
    c.moment = named(program, c.moment);
    c.second = named(program, c.second);
    wrench[i] = {named(program, wrench[i].moment), named(program, wrench[i].force)};
    const int parent = states[i].parent_state;
    if (parent < 0) continue;
    inertia[parent].mass += c.mass;
    inertia[parent].moment = inertia[parent].moment + c.moment;
    for (int k = 0; k < 9; ++k) inertia[parent].second[k] += c.second[k];
    wrench[parent].moment = wrench[parent].moment + wrench[i].moment;
    wrench[parent].force = wrench[parent].force + wrench[i].force;
  }

  // Kane's equations with the sums over bodies grouped by subtree. With
  // (w_r, v_r) the partial velocities of speed r at the world origin, the
  // partial velocity of a point p is v_r + w_r x p, so
  //   f_r  = sum_i (v_r + w_r x c_i).F_i + w_r.T_i = w_r.N_sub(r) + v_r.F_sub(r),
  //   M_rs = sum_i m_i v_r^i.v_s^i + w_r.I_i w_s = w_r.L_s + v_r.P_s,
  // where (L_s, P_s) is the momentum of the subtree of joint s moving with
  // u_s = 1 alone (r an ancestor of s or s itself; zero otherwise).
  std::vector<Vec3> w(n), v(n);
  for (int r = 0; r < n; ++r) tree.partial_velocities(r, w[r], v[r]);
  for (std::size_t i = 0; i < states.size(); ++i) {
    const kinematics::BodyState& b = states[i];
    if (!model.joints[b.joint].moves()) continue;
    const int s = tree.joints()[b.joint].speed;
    const SpatialInertia& c = inertia[i];
    const Vec3 angular = named(program, mul(c.second, w[s]) + cross(c.moment, v[s]));
    const Vec3 linear = named(program, c.mass * v[s] + cross(w[s], c.moment));
    eq.forcing[s] = dot(w[s], wrench[i].moment) + dot(v[s], wrench[i].force);
    for (int k : b.path) {
      const int r = tree.joints()[k].speed;
      eq.mass_matrix[s * n + r] = eq.mass_matrix[r * n + s] = dot(w[r], angular) + dot(v[r], linear);
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
    eq.potential_energy += stiffness * stretch * stretch / 2;
    eq.coordinate_rates.push_back(vars.u[r]);
    eq.coordinate_names.push_back(joint.name);
    eq.speed_names.push_back(joint.name + "_dot");
    eq.input_names.push_back(joint.name + "_tau");
  }

  for (const model::Output& out : model.outputs) {
    if (out.kind == model::OutputKind::point_position) {
      const int state = tree.state_of(out.body);
      Vec3 p = vec(vars, out.point);
      if (state >= 0) p = tree.point(tree.bodies()[state], p);
      const char* axes[] = {".x", ".y", ".z"};
      for (int i = 0; i < 3; ++i) {
        eq.outputs.push_back(p[i]);
        eq.output_names.push_back(out.name + axes[i]);
      }
      continue;
    }
    int r = -1;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
      if (model.joints[k].name == out.joint) r = tree.joints()[k].speed;
    eq.outputs.push_back(r < 0 ? ex(0) : out.kind == model::OutputKind::joint_coordinate ? ex(vars.q[r]) : ex(vars.u[r]));
    eq.output_names.push_back(out.name);
  }
  return eq;
}

}  // namespace kanegen::kane
