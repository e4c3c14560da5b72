// SPDX-License-Identifier: GPL-2.0-or-later
#include "kinematics/tree_kinematics.hpp"

#include <cmath>
#include <stdexcept>

namespace kanegen::kinematics {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using GiNaC::ex;

/// Floating-point round-off of an rpy of pi/2 leaves 6e-17 where the exact
/// matrix has 0; snapping keeps the sparsity that the generated code exploits.
ex snap(const ex& e) {
  if (!GiNaC::is_a<GiNaC::numeric>(e)) return e;
  const double v = GiNaC::ex_to<GiNaC::numeric>(e).to_double();
  for (int k : {-1, 0, 1})
    if (std::abs(v - k) < 1e-15) return k;
  return e;
}

Mat3 snapped(const Mat3& m) {
  Mat3 r;
  for (int i = 0; i < 9; ++i) r[i] = snap(m[i]);
  return r;
}

}  // namespace

Vec3 named_before_turn(Program& program, const Mat3& turn, const Vec3& v) {
  for (const ex& e : turn)
    if (GiNaC::is_a<GiNaC::numeric>(e) && !e.is_zero() && !e.is_equal(1) && !e.is_equal(-1))
      return named(program, v);
  return v;
}

Mat3 rotation_rpy(const ex& roll, const ex& pitch, const ex& yaw) {
  const ex cr = GiNaC::cos(roll), sr = GiNaC::sin(roll);
  const ex cp = GiNaC::cos(pitch), sp = GiNaC::sin(pitch);
  const ex cy = GiNaC::cos(yaw), sy = GiNaC::sin(yaw);
  const Mat3 rz{cy, -sy, 0, sy, cy, 0, 0, 0, 1};
  const Mat3 ry{cp, 0, sp, 0, 1, 0, -sp, 0, cp};
  const Mat3 rx{1, 0, 0, 0, cr, -sr, 0, sr, cr};
  return snapped(mul(rz, mul(ry, rx)));
}

Mat3 rotation_about(const Vec3& a, const ex& angle) {
  const ex c = GiNaC::cos(angle), s = GiNaC::sin(angle);
  const Mat3 skew{0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0};
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[3 * i + j] = (i == j ? c : ex(0)) + s * skew[3 * i + j] + (1 - c) * a[i] * a[j];
  return r;
}

Mat3 node_turn(const std::array<ex, 3>& theta) {
  Mat3 turn = identity_mat();
  for (int a = 0; a < 3; ++a) {
    if (theta[a].is_zero()) continue;
    Vec3 axis = zero_vec();
    axis[a] = 1;
    turn = mul(turn, rotation_about(axis, theta[a]));
  }
  return turn;
}

namespace {

/// sum_i c_i x_i over the nonzero c_i.
ex combine(const Eigen::VectorXd& c, const std::vector<ex>& x) {
  ex sum = 0;
  for (Eigen::Index i = 0; i < c.size(); ++i)
    if (c[i] != 0.0) sum += symbolic::number(c[i]) * x[static_cast<std::size_t>(i)];
  return sum;
}

/// How the joint frame on a node moves relative to the parent frame, in its
/// axes (all zero off nodes): the node's displacement from the parent origin
/// with its rate and rest acceleration, the turn's angular velocity and rest
/// angular acceleration.
struct NodeMotion {
  Vec3 node = zero_vec(), rate = zero_vec(), accel = zero_vec();
  Vec3 spin = zero_vec(), spin_accel = zero_vec();
};

/// The node's position = position + T eta + f, its rate and rest acceleration,
/// and the foreshortening's partial velocities: f_a = -1/2 eta^T H_a eta has
/// D_k,a = -(H_a eta)_k, rate D eta_dot and rest acceleration -eta_dot^T H_a eta_dot.
NodeMotion node_displacement(const NodeAttachment& a, const std::vector<ex>& eta,
                             const std::vector<ex>& eta_dot, Program& program,
                             std::vector<Vec3>& shortening_partial) {
  const int n = static_cast<int>(eta.size());
  NodeMotion m;
  for (int r = 0; r < 3; ++r) {
    m.node[r] = symbolic::number(a.position[r]) + combine(a.translation.row(r).transpose(), eta);
    m.rate[r] = combine(a.translation.row(r).transpose(), eta_dot);
  }
  shortening_partial.assign(n, zero_vec());
  for (std::size_t r = 0; r < a.shortening.size(); ++r) {
    const Eigen::MatrixXd& h = a.shortening[r];
    if (h.cwiseAbs().maxCoeff() == 0.0) continue;
    ex position = 0, rate = 0, accel = 0;
    for (int i = 0; i < n; ++i) {
      if (h.row(i).cwiseAbs().maxCoeff() == 0.0) continue;
      const ex h_eta = program.define(combine(h.row(i).transpose(), eta));
      const ex h_rate = program.define(combine(h.row(i).transpose(), eta_dot));
      shortening_partial[i][r] = -h_eta;
      position -= eta[i] * h_eta / 2;
      rate -= eta_dot[i] * h_eta;
      accel -= eta_dot[i] * h_rate;
    }
    m.node[r] += position;
    m.rate[r] += rate;
    m.accel[r] += accel;
  }
  m.node = named(program, m.node);
  m.rate = named(program, m.rate);
  return m;
}

/// The node's turn Rx(theta_x) Ry(theta_y) Rz(theta_z), factor by factor:
/// the axis of each factor is turned by those before it; its rate adds to
/// the spin, and the spin so far turns that axis (rest acceleration).
/// Sets the motion's spin and spin_accel and each speed's partial angular velocity.
Mat3 node_turn_motion(const NodeAttachment& a, const std::vector<ex>& eta, const std::vector<ex>& eta_dot,
                      Program& program, NodeMotion& m, std::vector<Vec3>& turn_partial) {
  const int n = static_cast<int>(eta.size());
  turn_partial.assign(n, zero_vec());
  Mat3 before = identity_mat();
  Vec3 spin = zero_vec(), spin_accel = zero_vec();
  for (int r = 0; r < 3; ++r) {
    const Eigen::VectorXd c = a.rotation.row(r).transpose();
    if (c.cwiseAbs().maxCoeff() == 0.0) continue;
    const ex theta = program.define(combine(c, eta));
    const ex rate = program.define(combine(c, eta_dot));
    Vec3 unit = zero_vec();
    unit[r] = 1;
    const Vec3 axis = mul(before, unit);
    spin_accel = spin_accel + rate * cross(spin, axis);
    spin = spin + rate * axis;
    for (int i = 0; i < n; ++i)
      if (c[i] != 0.0) turn_partial[i] = turn_partial[i] + symbolic::number(c[i]) * axis;
    before = mul(before, rotation_about(unit, theta));
  }
  const Mat3 turn = named(program, before);
  m.spin = named(program, spin);
  m.spin_accel = named(program, spin_accel);
  return turn;
}

/// On a node: the joint frame is the node frame, at node = position + T eta
/// (+ f) turned by the node's rotation; the node moves relative to the parent
/// frame with its rate + spin x (the joint origin from it). Turns the joint's
/// origin `xyz` and rotation `r_origin` by the node's turn and gives `b` the
/// elastic speeds' partial velocities.
NodeMotion attach_to_node(const NodeAttachment& a, const symbolic::Variables& vars, Program& program,
                          Vec3& xyz, Mat3& r_origin, BodyState& b) {
  const int n = static_cast<int>(a.rotation.cols());
  const std::vector<ex> eta(vars.q.begin() + a.first, vars.q.begin() + a.first + n);
  const std::vector<ex> eta_dot(vars.u.begin() + a.first, vars.u.begin() + a.first + n);
  std::vector<Vec3> shortening_partial, turn_partial;
  NodeMotion m = node_displacement(a, eta, eta_dot, program, shortening_partial);
  const Mat3 turn = node_turn_motion(a, eta, eta_dot, program, m, turn_partial);
  xyz = named(program, mul(turn, xyz));
  r_origin = named(program, mul(turn, r_origin));
  m.rate = named(program, m.rate + cross(m.spin, xyz));
  m.accel = named(program, m.accel + cross(m.spin, cross(m.spin, xyz)) + cross(m.spin_accel, xyz));
  b.node_first = a.first;
  for (int i = 0; i < n; ++i) {
    const Vec3& w = turn_partial[i];
    const Vec3 t{symbolic::number(a.translation(0, i)), symbolic::number(a.translation(1, i)),
                 symbolic::number(a.translation(2, i))};
    b.node_partial_angular.push_back(named(program, w));
    b.node_partial_linear.push_back(named(program, t + shortening_partial[i] - cross(w, m.node)));
  }
  return m;
}

/// The child's frame from its parent's: offset, axes and world pose, the
/// joint's motion and the node's displacement included. Child axes = joint
/// axes turned about a revolute axis; the axis has the same coordinates in both.
void place_child(BodyState& b, const BodyState& p, const JointFrame& frame, bool moves, int joint,
                 const symbolic::Variables& vars, Program& program, const Vec3& node, const Vec3& xyz,
                 const Mat3& r_origin) {
  Mat3 joint_to_child = identity_mat();  // transposed rotation of the joint motion
  b.offset = named(program, node + xyz);
  if (moves) {
    b.path.push_back(joint);
    const ex qk = vars.q[frame.speed];
    // A slide carries the origin along the axis (in parent axes), a turn the axes.
    if (frame.model.spherical()) {
      const ex &x = vars.q[frame.speed], &y = vars.q[frame.speed + 1], &z = vars.q[frame.speed + 2];
      const ex& w = vars.q[frame.quaternion_w];
      const ex s = program.define(2 / (w * w + x * x + y * y + z * z));
      joint_to_child = named(program, transpose(JointModel::quaternion_rotation(x, y, z, w, s)));
    } else if (frame.model.slides())
      b.offset = named(program, node + xyz + frame.model.translation(mul(r_origin, frame.axis), qk));
    else
      joint_to_child = named(program, transpose(frame.model.rotation(frame.axis, qk)));
  }
  b.to_child = named(program, mul(joint_to_child, transpose(r_origin)));
  b.rotation = named(program, mul(p.rotation, transpose(b.to_child)));
  b.origin = named(program, p.origin + mul(p.rotation, b.offset));
}

/// The child's velocities and rest accelerations (u_dot = 0) from its
/// parent's, in child axes: the outward recursion, with the node's motion.
void child_motion(BodyState& b, const BodyState& p, const JointFrame& frame, bool moves, bool on_node,
                  const symbolic::Variables& vars, Program& program, const NodeMotion& m) {
  const Vec3& r = b.offset;
  const Vec3 relative_velocity =
      moves ? frame.model.linear_velocity(frame.axis, vars.u[frame.speed]) : zero_vec();
  // The joint frame's angular velocity and rest acceleration (the node's turn included).
  const Vec3 frame_omega = on_node ? named(program, p.omega + m.spin) : p.omega;
  const Vec3 frame_alpha =
      on_node ? named(program, p.alpha_rest + cross(p.omega, m.spin) + m.spin_accel) : p.alpha_rest;
  const Vec3 parent_omega = named(program, mul(b.to_child, frame_omega));  // in child axes
  if (moves && frame.model.turns()) {
    // w = E w_p + sum_c a_c u_c; the axes, fixed in the child, turn with
    // the parent's E w_p relative to the joint frame: + u_c (E w_p) x a_c.
    Vec3 omega = parent_omega, alpha = mul(b.to_child, frame_alpha);
    for (int c = 0; c < frame.speeds(); ++c) {
      const ex uk = vars.u[frame.speed + c];
      omega = omega + frame.model.angular_velocity(frame.column(c), uk);
      alpha = alpha + uk * cross(parent_omega, frame.column(c));
    }
    b.omega = named(program, omega);
    b.alpha_rest = named(program, alpha);
  } else {
    b.omega = parent_omega;
    b.alpha_rest = named(program, mul(b.to_child, frame_alpha));
  }
  const Vec3 coriolis = 2 * cross(parent_omega, relative_velocity);
  const Mat3& e = b.to_child;
  const Vec3 spin_r = named_before_turn(program, e, cross(p.omega, r));  // shared by both
  const Vec3 velocity_in_parent = named_before_turn(program, e, p.velocity + spin_r + m.rate);
  b.velocity = named(program, mul(e, velocity_in_parent) + relative_velocity);
  const Vec3 accel_in_parent = named_before_turn(
      program, e,
      p.accel_rest + cross(p.alpha_rest, r) + cross(p.omega, spin_r) + 2 * cross(p.omega, m.rate) + m.accel);
  b.accel_rest = named(program, mul(e, accel_in_parent) + coriolis);
}

}  // namespace

TreeKinematics::TreeKinematics(const model::Model& model, const symbolic::Variables& vars,
                               symbolic::Program& program, const Vec3& base_acceleration,
                               const std::map<int, NodeAttachment>& attachments)
    : model_(model), program_(program), joints_(model.joints.size()) {
  // Speeds are numbered in file order of the moving joints (symbolic/variables.hpp).
  for (std::size_t k = 0; k < model.joints.size(); ++k) {
    joints_[k].speed = vars.first_speed.at(k);
    const auto w = vars.quaternion_w.find(static_cast<int>(k));
    if (w != vars.quaternion_w.end()) joints_[k].quaternion_w = w->second;
  }

  BodyState ground;
  ground.to_child = ground.rotation = identity_mat();
  ground.offset = ground.origin = ground.omega = ground.velocity = ground.alpha_rest = zero_vec();
  ground.accel_rest = base_acceleration;

  // Place bodies parents first: repeatedly take the joints whose parent is placed.
  std::vector<bool> placed(model.joints.size(), false);
  for (bool progress = true; progress;) {
    progress = false;
    for (std::size_t k = 0; k < model.joints.size(); ++k) {
      const model::Joint& joint = model.joints[k];
      const int parent = joint.parent == model.ground ? -1 : state_of(joint.parent);
      if (placed[k] || (parent < 0 && joint.parent != model.ground)) continue;
      placed[k] = progress = true;
      const auto attached = attachments.find(static_cast<int>(k));
      bodies_.push_back(place(k, parent, parent < 0 ? ground : bodies_[parent], vars,
                              attached == attachments.end() ? nullptr : &attached->second));
    }
  }
}

BodyState TreeKinematics::place(std::size_t k, int parent, const BodyState& p,
                                const symbolic::Variables& vars, const NodeAttachment* attachment) {
  const model::Joint& joint = model_.joints[k];
  BodyState b;
  for (std::size_t i = 0; i < model_.bodies.size(); ++i)
    if (model_.bodies[i].name == joint.child) b.body = static_cast<int>(i);
  if (b.body < 0) throw std::logic_error("joint child not found: " + joint.child);
  b.parent_state = parent;
  b.joint = static_cast<int>(k);
  b.path = p.path;

  Vec3 xyz{vars.scalar(joint.origin_xyz[0]), vars.scalar(joint.origin_xyz[1]),
           vars.scalar(joint.origin_xyz[2])};
  Mat3 r_origin = rotation_rpy(vars.scalar(joint.origin_rpy[0]), vars.scalar(joint.origin_rpy[1]),
                               vars.scalar(joint.origin_rpy[2]));
  JointFrame& frame = joints_[k];
  frame.origin_xyz = xyz;
  frame.origin_rotation = r_origin;
  frame.on_node = attachment != nullptr;
  if (frame.speed >= 0) frame.coordinate = vars.q[frame.speed];
  NodeMotion m;
  if (attachment) m = attach_to_node(*attachment, vars, program_, xyz, r_origin, b);
  frame.model = JointModel(joint.type);
  for (int i = 0; i < 3; ++i) frame.axis[i] = snap(symbolic::number(joint.axis[i]));

  place_child(b, p, frame, joint.moves(), static_cast<int>(k), vars, program_, m.node, xyz, r_origin);
  child_motion(b, p, frame, joint.moves(), attachment != nullptr, vars, program_, m);
  return b;
}

int TreeKinematics::state_of(const std::string& body_name) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (model_.bodies[bodies_[i].body].name == body_name) return static_cast<int>(i);
  return -1;
}

Vec3 TreeKinematics::world_point(const BodyState& b, const Vec3& local) const {
  return named(program_, b.origin + mul(b.rotation, local));
}

}  // namespace kanegen::kinematics
