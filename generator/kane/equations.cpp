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

  for (const kinematics::BodyState& b : tree.bodies()) {
    const model::Body& body = model.bodies[b.body];
    const ex mass = vars.scalar(body.mass);
    const auto& in = body.inertia;
    const Mat3 local{vars.scalar(in[0]), vars.scalar(in[3]), vars.scalar(in[4]),
                     vars.scalar(in[3]), vars.scalar(in[1]), vars.scalar(in[5]),
                     vars.scalar(in[4]), vars.scalar(in[5]), vars.scalar(in[2])};
    const Mat3 inertia = world_inertia(program, b.rotation, local);
    const Vec3 com = tree.point(b, vec(vars, body.com));
    const Vec3 com_velocity = tree.point_velocity(b, com);
    const Vec3 com_accel = tree.point_accel_rest(b, com);
    const Vec3 spin = named(program, mul(inertia, b.omega));  // I w

    // Resultant applied-plus-inertia force at the centre of mass and torque.
    Vec3 force = mass * (gravity - com_accel);
    Vec3 torque = symbolic::zero_vec() - mul(inertia, b.alpha_rest) - cross(b.omega, spin);
    for (const model::PointForce& pf : model.forces) {
      if (pf.body != body.name) continue;
      const Vec3 local_force = vec(vars, pf.force);
      const Vec3 f = pf.frame == model::ForceFrame::world ? local_force : mul(b.rotation, local_force);
      const Vec3 at = tree.point(b, vec(vars, pf.point));
      force = force + f;
      torque = torque + cross(at - com, f);
      if (pf.frame == model::ForceFrame::world) eq.potential_energy -= dot(f, at);
    }
    force = named(program, force);
    torque = named(program, torque);

    eq.kinetic_energy += (mass * dot(com_velocity, com_velocity) + dot(b.omega, spin)) / 2;
    eq.potential_energy -= mass * dot(gravity, com);

    // Partial velocities for the speeds on this body's path.
    std::vector<int> speeds;
    std::vector<Vec3> v, w, mv, iw;
    for (int k : b.path) {
      const int r = tree.joints()[k].speed;
      speeds.push_back(r);
      v.push_back(tree.partial_velocity(b, com, r));
      w.push_back(tree.partial_angular_velocity(b, r));
      mv.push_back(named(program, mass * v.back()));
      iw.push_back(named(program, mul(inertia, w.back())));
    }
    for (std::size_t a = 0; a < speeds.size(); ++a) {
      eq.forcing[speeds[a]] += dot(v[a], force) + dot(w[a], torque);
      for (std::size_t c = 0; c <= a; ++c) eq.mass_matrix[speeds[a] * n + speeds[c]] += dot(mv[a], v[c]) + dot(w[a], iw[c]);
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
  for (int r = 0; r < n; ++r)
    for (int s = r + 1; s < n; ++s) eq.mass_matrix[r * n + s] = eq.mass_matrix[s * n + r];

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
