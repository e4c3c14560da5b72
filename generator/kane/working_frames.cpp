// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/working_frames.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

#include "symbolic/variables.hpp"

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using GiNaC::ex;

constexpr double tolerance = 1e-12;

/// A constant as an exact 0 or +-1 where it is one to rounding, so that the
/// structural zeros of the steps fold.
ex exact(double v) {
  for (int k : {-1, 0, 1})
    if (std::abs(v - k) < tolerance) return k;
  return number(v);
}

Mat3 to_mat(const Matrix3d& m) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[3 * i + j] = exact(m(i, j));
  return r;
}

/// The value of a constant expression, or false if it is not one.
bool value_of(const ex& e, double& v) {
  const ex n = e.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(n) || !GiNaC::ex_to<GiNaC::numeric>(n).is_real()) return false;
  v = GiNaC::ex_to<GiNaC::numeric>(n).to_double();
  return true;
}

Mat3 rot_z(const ex& c, const ex& s) { return {c, -s, 0, s, c, 0, 0, 0, 1}; }
Mat3 rot_x(const ex& c, const ex& s) { return {1, 0, 0, 0, c, -s, 0, s, c}; }
Matrix3d rot_z(double angle) { return Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix(); }
Matrix3d rot_x(double angle) { return Eigen::AngleAxisd(angle, Vector3d::UnitX()).toRotationMatrix(); }

/// A rotation taking the unit axis a to e_z: a signed permutation when a is
/// a coordinate axis, so that turning into it costs nothing.
Matrix3d axis_to_z(const Vector3d& a) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(a[i]) < std::abs(a[k]) - tolerance) k = i;
  const Vector3d x = (Vector3d::Unit(k) - a[k] * a).normalized();
  Matrix3d p;
  p.row(0) = x.transpose();
  p.row(1) = a.cross(x).transpose();
  p.row(2) = a.transpose();
  return p;
}

/// The constant parts of a joint's transform, H = Rz(gamma) Rx(alpha)
/// Rz(theta) and v = Rz(gamma) [(a, 0, eps) + delta Rx(alpha) e_z]. With
/// parallel axes (sin alpha = 0) gamma turns v's offset across the axes
/// onto x and delta = 0.
struct Khalil {
  double gamma = 0, alpha = 0, theta = 0, a = 0, delta = 0, eps = 0;
};

Khalil decompose(const Matrix3d& h, const Vector3d& v) {
  Khalil k;
  const double sa = std::hypot(h(0, 2), h(1, 2)), ca = h(2, 2);
  const bool parallel = sa < 1e-9;
  k.alpha = std::atan2(sa, ca);
  if (!parallel) {
    k.gamma = std::atan2(h(0, 2), -h(1, 2));
    k.theta = std::atan2(h(2, 0), h(2, 1));
  } else {
    k.alpha = ca > 0 ? 0.0 : std::acos(-1.0);
    k.gamma = std::hypot(v[0], v[1]) > tolerance ? std::atan2(v[1], v[0]) : 0.0;
    const double turn = std::atan2(h(1, 0), h(0, 0));
    k.theta = ca > 0 ? turn - k.gamma : k.gamma - turn;
  }
  const Vector3d u = rot_z(-k.gamma) * v;
  k.a = u[0];
  k.delta = parallel ? 0.0 : -u[1] / sa;
  k.eps = u[2] - k.delta * std::cos(k.alpha);
  return k;
}

/// Per body: its working axes P = Rz(phi) Pi and origin slid by t along its axis.
struct Choice {
  Matrix3d pi = Matrix3d::Identity();
  double phi = 0, t = 0;
  bool free = false;  ///< rigid: phi and t may be chosen
  Matrix3d axes() const { return rot_z(phi) * pi; }
};

/// The joint's constant origin, or false where it depends on parameters.
bool constant_origin(const kinematics::JointFrame& joint, Matrix3d& rotation, Vector3d& xyz) {
  for (int i = 0; i < 9; ++i)
    if (!value_of(joint.origin_rotation[i], rotation(i / 3, i % 3))) return false;
  for (int i = 0; i < 3; ++i)
    if (!value_of(joint.origin_xyz[i], xyz[i])) return false;
  return true;
}

void add_turn(std::vector<FrameStep>& steps, const Mat3& turn) {
  if (FrameStep step{turn, zero_vec()}; step.turns()) steps.push_back(step);
}
void add_shift(std::vector<FrameStep>& steps, const Vec3& shift) {
  if (FrameStep step{identity_mat(), shift}; step.shifts()) steps.push_back(step);
}

/// The steps must be the body frames' transform, P_p R_o P^T and P_p xyz +
/// s_p - (that) s at q = 0 (s = -t e_z): a wrong angle here would be a wrong
/// model, so it is checked rather than trusted.
void check_khalil(const Khalil& k, const Choice& parent, const Choice& child, const Matrix3d& rotation,
                  const Vector3d& xyz) {
  const Matrix3d outer = rot_z(k.gamma) * rot_x(k.alpha);
  const Matrix3d turn = outer * rot_z(k.theta - child.phi);
  const Vector3d shift = rot_z(k.gamma) * Vector3d(k.a, 0, k.eps) + (k.delta + child.t) * outer.col(2);
  const Matrix3d expected_turn = parent.axes() * rotation * child.axes().transpose();
  const Vector3d expected_shift =
      parent.axes() * xyz - parent.t * Vector3d::UnitZ() + child.t * expected_turn.col(2);
  const double scale = 1 + xyz.norm();
  if ((turn - expected_turn).norm() > 1e-9 || (shift - expected_shift).norm() > 1e-9 * scale)
    throw std::logic_error(
        "working_frames: a joint's Khalil-Kleinfinger parameters do not reproduce its origin");
}

/// The steps of a DH-ready joint: x_parent = Rz(gamma) [(a, 0, eps) + Rx(alpha) (delta e_z + Rz(theta) x)].
std::vector<FrameStep> khalil_steps(const Khalil& k, const kinematics::JointFrame& joint, const Choice& child,
                                    Program& program) {
  std::vector<FrameStep> steps;
  add_turn(steps, rot_z(exact(std::cos(k.gamma)), exact(std::sin(k.gamma))));
  add_shift(steps, {exact(k.a), 0, exact(k.eps)});
  add_turn(steps, rot_x(exact(std::cos(k.alpha)), exact(std::sin(k.alpha))));
  const bool moves = joint.speed >= 0;
  const double theta0 = k.theta - child.phi;
  ex delta = exact(k.delta + child.t);
  if (moves && joint.model.slides()) delta = program.define(delta + joint.coordinate);
  add_shift(steps, {0, 0, delta});
  const ex c0 = exact(std::cos(theta0)), s0 = exact(std::sin(theta0));
  if (moves && joint.model.turns()) {
    // cos and sin of q + theta0 at once, where the sum formulas would cost
    // six operations; with theta0 a multiple of pi/2 they cost none.
    const bool plain = c0.is_zero() || s0.is_zero();
    const ex angle = plain ? joint.coordinate : program.define(joint.coordinate + number(theta0));
    const ex c = GiNaC::cos(angle), s = GiNaC::sin(angle);
    if (plain)
      add_turn(steps, rot_z(program.define(c * c0 - s * s0), program.define(s * c0 + c * s0)));
    else
      add_turn(steps, rot_z(program.define(c), program.define(s)));
  } else {
    add_turn(steps, rot_z(c0, s0));
  }
  return steps;
}

}  // namespace

bool FrameStep::turns() const {
  const Mat3 identity = identity_mat();
  for (int i = 0; i < 9; ++i)
    if (!turn[i].is_equal(identity[i])) return true;
  return false;
}

bool FrameStep::shifts() const {
  for (const ex& x : shift)
    if (!x.is_zero()) return true;
  return false;
}

std::vector<WorkingFrame> working_frames(const kinematics::TreeKinematics& tree,
                                         const std::vector<bool>& flexible, Program& program) {
  const auto& states = tree.bodies();
  const std::size_t count = states.size();
  std::vector<Choice> choice(count);
  std::vector<bool> khalil_ready(count, false);
  std::vector<Matrix3d> origin_rotation(count, Matrix3d::Identity());
  std::vector<Vector3d> origin_xyz(count, Vector3d::Zero());
  for (std::size_t i = 0; i < count; ++i) {
    const kinematics::JointFrame& joint = tree.joints()[states[i].joint];
    const bool spherical = joint.model.spherical();
    choice[i].free = !flexible[i] && !spherical;
    if (choice[i].free && joint.speed >= 0) {
      Vector3d axis;
      for (int k = 0; k < 3; ++k) value_of(joint.axis[k], axis[k]);
      choice[i].pi = axis_to_z(axis);
    }
    khalil_ready[i] = states[i].parent_state >= 0 && !flexible[i] && !spherical && !joint.on_node &&
                      constant_origin(joint, origin_rotation[i], origin_xyz[i]);
  }
  // Each rigid body turns and slides its frame for its first such child.
  std::vector<bool> chosen(count, false);
  for (std::size_t i = 0; i < count; ++i) {
    const int p = states[i].parent_state;
    if (!khalil_ready[i] || !choice[p].free || chosen[p]) continue;
    const Khalil k =
        decompose(choice[p].pi * origin_rotation[i] * choice[i].pi.transpose(), choice[p].pi * origin_xyz[i]);
    choice[p].phi = -k.gamma;
    choice[p].t = k.eps;
    chosen[p] = true;
  }

  std::vector<WorkingFrame> frames(count);
  for (std::size_t i = 0; i < count; ++i) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    WorkingFrame& f = frames[i];
    f.from_body = {to_mat(choice[i].axes()), {0, 0, exact(-choice[i].t)}};
    f.axis = flexible[i] ? joint.axis : Vec3{0, 0, 1};
    const int p = state.parent_state;
    if (p < 0) continue;
    const FrameStep& parent = frames[p].from_body;
    const Mat3 inverse_turn = transpose(f.from_body.turn);
    if (!khalil_ready[i]) {  // one general step: P_p E^T P^T, P_p r + s_p - (that) s
      const Mat3 turn = named(program, mul(parent.turn, mul(transpose(state.to_child), inverse_turn)));
      f.to_parent.push_back({turn, named(program, mul(parent.turn, state.offset) + parent.shift -
                                                      mul(turn, f.from_body.shift))});
      continue;
    }
    const Vector3d v = choice[p].pi * origin_xyz[i];
    Khalil k = decompose(choice[p].pi * origin_rotation[i] * choice[i].pi.transpose(), v);
    k.gamma += choice[p].phi;
    k.eps -= choice[p].t;
    f.to_parent = khalil_steps(k, joint, choice[i], program);
    check_khalil(k, choice[p], choice[i], origin_rotation[i], origin_xyz[i]);
  }
  return frames;
}

}  // namespace kanegen::kane
