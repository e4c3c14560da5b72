// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/articulated_body.hpp"

#include <cstddef>

namespace kanegen::kane {
using namespace kanegen::symbolic;  // the vector algebra and its operators
namespace {

using GiNaC::ex;

/// A spatial inertia about a body's origin in its axes, as blocks acting on
/// the motion (alpha, a): moment = A alpha + B a, force = B^T alpha + C a;
/// A and C symmetric. With the bias wrench p: what the subtree needs,
/// moment and force, to move with (alpha, a).
struct Articulated {
  Mat3 a, b, c;
  Vec3 bias_moment = zero_vec(), bias_force = zero_vec();
};

/// The joint's terms of the recursion: U = I^A S, W = U / D, g = (Q - S^T p) / D.
struct JointTerms {
  Vec3 u_moment, u_force, w_moment, w_force;
  ex residual_over_pivot = 0;
};

ex at(const Mat3& m, int i, int j) { return m[3 * i + j]; }

/// The skew matrix [r]x of r x (.).
Mat3 skew(const Vec3& r) { return {0, -r[2], r[1], r[2], 0, -r[0], -r[1], r[0], 0}; }

/// Names the upper triangle of a symmetric matrix and mirrors it.
Mat3 named_symmetric(Program& program, const Mat3& m) {
  Mat3 s;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) s[3 * i + j] = s[3 * j + i] = program.define(m[3 * i + j]);
  return s;
}

/// E^T M E, M in child axes, E: parent -> child axes. `symmetric`: only
/// the upper triangle is formed.
Mat3 to_parent_axes(Program& program, const Mat3& to_child, const Mat3& m, bool symmetric) {
  const Mat3 me = named(program, mul(m, to_child));
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = symmetric ? i : 0; j < 3; ++j) {
      const ex entry =
          program.define(to_child[i] * me[j] + to_child[3 + i] * me[3 + j] + to_child[6 + i] * me[6 + j]);
      r[3 * i + j] = entry;
      if (symmetric) r[3 * j + i] = entry;
    }
  return r;
}

/// X^T I X: the child's articulated inertia and bias about the parent's
/// origin, in parent axes (r: parent origin -> child origin, parent axes).
/// With S = [r]x: A' = A - B S + S B^T - S C S, B' = B + S C, C' = C (rotated
/// first); formed as A' = A - B' S - (B S)^T, which reuses B' for S C S.
Articulated to_parent(Program& program, const Articulated& child, const Mat3& to_child, const Vec3& r) {
  const Mat3 a = to_parent_axes(program, to_child, child.a, true);
  const Mat3 b = to_parent_axes(program, to_child, child.b, false);
  const Mat3 c = to_parent_axes(program, to_child, child.c, true);
  const Mat3 s = skew(r);
  const Mat3 cs = mul(c, s);  // S C = -(C S)^T
  Articulated p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.b[3 * i + j] = program.define(at(b, i, j) - at(cs, j, i));
  const Mat3 bs = mul(b, s), shifted_bs = mul(p.b, s);
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      p.a[3 * i + j] = p.a[3 * j + i] = program.define(at(a, i, j) - at(shifted_bs, i, j) - at(bs, j, i));
  p.c = c;
  p.bias_force = named(program, mul_transposed(to_child, child.bias_force));
  p.bias_moment = named(program, mul_transposed(to_child, child.bias_moment) + cross(r, p.bias_force));
  return p;
}

/// The body's own spatial inertia, and minus its wrench as the bias.
Articulated own_terms(const TreeBody& body) {
  Articulated s;
  s.a = body.second;
  s.b = skew(body.moment);  // moment: h x a; force: alpha x h = [h]x^T alpha
  s.c = Mat3{body.mass, 0, 0, 0, body.mass, 0, 0, 0, body.mass};
  s.bias_moment = zero_vec() - body.wrench_moment;
  s.bias_force = zero_vec() - body.wrench_force;
  return s;
}

/// The coordinate (0, 1, 2) along which a unit axis lies, or -1.
int coordinate_of(const Vec3& axis) {
  int found = -1;
  for (int k = 0; k < 3; ++k) {
    if (axis[k].is_zero()) continue;
    if (found >= 0 || !(axis[k].is_equal(1) || axis[k].is_equal(-1))) return -1;
    found = k;
  }
  return found;
}

/// I^A - U U^T / D annihilates S exactly, but symbolically D/D stays a
/// quotient: when S is along coordinate k, the passed inertia's entries that
/// act on S (revolute: row and column k of A, row k of B; prismatic: row
/// and column k of C, column k of B) are set to the zero they are, so the
/// transform to the parent skips them. W's own entry S^T W = 1 likewise.
void drop_joint_direction(Articulated& passed, JointTerms& terms, const kinematics::JointFrame& joint) {
  const int k = coordinate_of(joint.axis);
  if (k < 0) return;
  Mat3& diagonal = joint.prismatic ? passed.c : passed.a;
  for (int j = 0; j < 3; ++j) {
    diagonal[3 * k + j] = diagonal[3 * j + k] = 0;
    (joint.prismatic ? passed.b[3 * j + k] : passed.b[3 * k + j]) = 0;
  }
  (joint.prismatic ? terms.w_force : terms.w_moment)[k] = joint.axis[k];
}

void add(Articulated& sum, const Articulated& x) {
  for (int k = 0; k < 9; ++k) {
    sum.a[k] += x.a[k];
    sum.b[k] += x.b[k];
    sum.c[k] += x.c[k];
  }
  sum.bias_moment = sum.bias_moment + x.bias_moment;
  sum.bias_force = sum.bias_force + x.bias_force;
}

Articulated named(Program& program, const Articulated& x) {
  return {named_symmetric(program, x.a), named(program, x.b), named_symmetric(program, x.c),
          named(program, x.bias_moment), named(program, x.bias_force)};
}

}  // namespace

RecursiveDynamics articulated_body_dynamics(const kinematics::TreeKinematics& tree,
                                            const std::vector<TreeBody>& bodies,
                                            const std::vector<ex>& joint_forces, Program& program) {
  const auto& states = tree.bodies();
  const std::size_t count = states.size();
  const std::size_t speeds = joint_forces.size();
  RecursiveDynamics out;
  out.accelerations.assign(speeds, 0);
  out.pivots.assign(speeds, 0);

  // Inward: children come after their parents, so a reverse sweep has every
  // child's share added before its parent is named.
  std::vector<Articulated> sums(count);
  for (std::size_t i = 0; i < count; ++i) sums[i] = own_terms(bodies[i]);
  std::vector<JointTerms> terms(count);
  for (std::size_t i = count; i-- > 0;) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    Articulated passed = named(program, sums[i]);
    if (joint.speed >= 0) {
      const int s = joint.speed;
      const Vec3& axis = joint.axis;
      JointTerms& t = terms[i];
      if (joint.prismatic) {
        t.u_moment = named(program, mul(passed.b, axis));
        t.u_force = named(program, mul(passed.c, axis));
      } else {
        t.u_moment = named(program, mul(passed.a, axis));
        t.u_force = named(program, mul_transposed(passed.b, axis));
      }
      const ex pivot = program.define(dot(axis, joint.prismatic ? t.u_force : t.u_moment));
      if (pivot.is_zero()) return {{}, {}, {}, s};  // 1/D does not exist
      const ex inverse = program.define(1 / pivot);
      const ex residual =
          joint_forces[s] - dot(axis, joint.prismatic ? passed.bias_force : passed.bias_moment);
      t.w_moment = named(program, inverse * t.u_moment);
      t.w_force = named(program, inverse * t.u_force);
      t.residual_over_pivot = program.define(inverse * residual);
      out.pivots[s] = pivot;
      out.pivot_order.push_back(s);
      if (state.parent_state < 0) continue;  // nothing passed to the ground
      // I^A - U W^T (symmetric) and p^A + U g.
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          passed.b[3 * r + c] -= t.u_moment[r] * t.w_force[c];
          if (c < r) continue;
          passed.a[3 * r + c] -= t.u_moment[r] * t.w_moment[c];
          passed.c[3 * r + c] -= t.u_force[r] * t.w_force[c];
          passed.a[3 * c + r] = passed.a[3 * r + c];
          passed.c[3 * c + r] = passed.c[3 * r + c];
        }
      passed.bias_moment = passed.bias_moment + t.residual_over_pivot * t.u_moment;
      passed.bias_force = passed.bias_force + t.residual_over_pivot * t.u_force;
      drop_joint_direction(passed, t, joint);
    }
    if (state.parent_state < 0) continue;
    add(sums[state.parent_state], to_parent(program, named(program, passed), state.to_child, state.offset));
  }

  // Outward: the accelerations that u_dot gives, the ground's zero.
  std::vector<Vec3> alpha(count, zero_vec()), accel(count, zero_vec());
  for (std::size_t i = 0; i < count; ++i) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    Vec3 angular = zero_vec(), linear = zero_vec();
    if (state.parent_state >= 0) {
      const Vec3& parent_alpha = alpha[state.parent_state];
      angular = named(program, mul(state.to_child, parent_alpha));
      linear =
          named(program, mul(state.to_child, accel[state.parent_state] + cross(parent_alpha, state.offset)));
    }
    if (joint.speed >= 0) {
      const JointTerms& t = terms[i];
      const ex udot =
          program.define(t.residual_over_pivot - dot(t.w_moment, angular) - dot(t.w_force, linear));
      out.accelerations[joint.speed] = udot;
      if (joint.prismatic)
        linear = named(program, linear + udot * joint.axis);
      else
        angular = named(program, angular + udot * joint.axis);
    }
    alpha[i] = angular;
    accel[i] = linear;
  }
  return out;
}

}  // namespace kanegen::kane
