// SPDX-License-Identifier: GPL-2.0-or-later
#include "kane/articulated_body.hpp"

#include <cstddef>

#include "kane/working_frames.hpp"
#include "kane/working_motion.hpp"

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
  /// A flexible body's elastic rows and columns (empty for a rigid one):
  /// per elastic speed k, the wrench (moment, force) that eta_ddot_k = 1
  /// needs; the m x m elastic block (row-major, symmetric); the elastic bias.
  std::vector<Vec3> elastic_moment, elastic_force;
  std::vector<ex> elastic_block, elastic_bias;
};

/// A flexible body's local speeds (elastic first, then its joint's if any)
/// after the LDL^T of D = L diag(d) L^T: V = L^-1 U^T (rows of 6, top part
/// of U), W_j = V_j / d_j, g_j = (L^-1 (Q - S^T p))_j / d_j.
struct BlockTerms {
  std::vector<int> speeds;
  std::vector<ex> lower;  ///< L, n x n row-major, unit diagonal
  std::vector<Vec3> w_moment, w_force;
  std::vector<ex> residual_over_pivot;
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

/// The coordinate axis a turn is about, or -1.
int turn_axis(const Mat3& turn) {
  for (int k = 0; k < 3; ++k) {
    bool fixed = turn[4 * k].is_equal(1);
    for (int j = 0; j < 3 && fixed; ++j)
      fixed = j == k || (turn[3 * k + j].is_zero() && turn[3 * j + k].is_zero());
    if (fixed) return k;
  }
  return -1;
}

/// sin^2, sin cos and cos 2theta of a turn: what turning a symmetric matrix needs.
struct DoubleAngle {
  ex c, s, ss, cs, c2;
  DoubleAngle(Program& program, const ex& cosine, const ex& sine)
      : c(cosine),
        s(sine),
        ss(program.define(sine * sine)),
        cs(program.define(cosine * sine)),
        c2(program.define(1 - 2 * ss)) {}
};

/// R M R^T for symmetric M and R a turn about coordinate axis k: with (i, j,
/// k) cyclic and delta = M_ii - M_jj, u = sin^2 delta + 2 sin cos M_ij,
/// M'_ii = M_ii - u, M'_jj = M_jj + u, M'_ij = sin cos delta + cos 2theta
/// M_ij; 15 operations instead of 33.
Mat3 turned_symmetric(Program& program, const Mat3& m, int k, const DoubleAngle& t) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const ex delta = program.define(at(m, i, i) - at(m, j, j));
  const ex u = program.define(t.ss * delta + 2 * t.cs * at(m, i, j));
  Mat3 r;
  r[4 * i] = program.define(at(m, i, i) - u);
  r[4 * j] = program.define(at(m, j, j) + u);
  r[3 * i + j] = r[3 * j + i] = program.define(t.cs * delta + t.c2 * at(m, i, j));
  r[3 * i + k] = r[3 * k + i] = program.define(t.c * at(m, i, k) - t.s * at(m, j, k));
  r[3 * j + k] = r[3 * k + j] = program.define(t.s * at(m, i, k) + t.c * at(m, j, k));
  r[4 * k] = at(m, k, k);
  return r;
}

/// R M R^T for any M and R a turn about coordinate axis k: the (i, j)
/// block's symmetric part turns as turned_symmetric's, its antisymmetric
/// part (M_ij - M_ji) / 2 not at all; row and column k turn as vectors.
/// 15 operations for the block instead of 24.
Mat3 turned_general(Program& program, const Mat3& m, int k, const DoubleAngle& t) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const ex delta = program.define(at(m, i, i) - at(m, j, j));
  const ex sum = program.define(at(m, i, j) + at(m, j, i));
  const ex u = program.define(t.ss * delta + t.cs * sum);
  const ex symmetric = program.define(t.cs * delta + t.c2 * sum / 2);
  const ex antisymmetric = program.define((at(m, i, j) - at(m, j, i)) / 2);
  Mat3 r;
  r[4 * i] = program.define(at(m, i, i) - u);
  r[4 * j] = program.define(at(m, j, j) + u);
  r[3 * i + j] = program.define(symmetric + antisymmetric);
  r[3 * j + i] = program.define(symmetric - antisymmetric);
  r[3 * i + k] = program.define(t.c * at(m, i, k) - t.s * at(m, j, k));
  r[3 * j + k] = program.define(t.s * at(m, i, k) + t.c * at(m, j, k));
  r[3 * k + i] = program.define(t.c * at(m, k, i) - t.s * at(m, k, j));
  r[3 * k + j] = program.define(t.s * at(m, k, i) + t.c * at(m, k, j));
  r[4 * k] = at(m, k, k);
  return r;
}

/// The inertia and bias in axes turned by `turn` (inner -> outer axes).
Articulated turned(Program& program, const Articulated& x, const Mat3& turn) {
  const Mat3 to_inner = transpose(turn);
  Articulated r;
  if (const int k = turn_axis(turn); k >= 0) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const DoubleAngle angle(program, turn[4 * i], turn[3 * j + i]);
    r.b = turned_general(program, x.b, k, angle);
    r.a = turned_symmetric(program, x.a, k, angle);
    r.c = turned_symmetric(program, x.c, k, angle);
  } else {
    r.b = to_parent_axes(program, to_inner, x.b, false);
    r.a = to_parent_axes(program, to_inner, x.a, true);
    r.c = to_parent_axes(program, to_inner, x.c, true);
  }
  r.bias_force = named(program, mul(turn, x.bias_force));
  r.bias_moment = named(program, mul(turn, x.bias_moment));
  return r;
}

/// X^T I X for a shift: about an origin from which x's is at r. With S =
/// [r]x: A' = A - B S + S B^T - S C S, B' = B + S C, C' = C; formed as
/// A' = A - B' S - (B S)^T, which reuses B' for S C S.
Articulated shifted(Program& program, const Articulated& x, const Vec3& r) {
  const Mat3 s = skew(r);
  const Mat3 cs = mul(x.c, s);  // S C = -(C S)^T
  Articulated p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.b[3 * i + j] = program.define(at(x.b, i, j) - at(cs, j, i));
  const Mat3 bs = mul(x.b, s), shifted_bs = mul(p.b, s);
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      p.a[3 * i + j] = p.a[3 * j + i] = program.define(at(x.a, i, j) - at(shifted_bs, i, j) - at(bs, j, i));
  p.c = x.c;
  p.bias_force = x.bias_force;
  p.bias_moment = named(program, x.bias_moment + cross(r, x.bias_force));
  return p;
}

/// A rigid articulated inertia carried from a frame to the outer one.
Articulated carried(Program& program, Articulated x, const FrameStep& step) {
  if (step.turns()) x = turned(program, x, step.turn);
  if (step.shifts()) x = shifted(program, x, step.shift);
  return x;
}

/// The body's own spatial inertia, and minus its wrench as the bias.
Articulated own_terms(const TreeBody& body) {
  Articulated s;
  s.a = body.second;
  s.b = skew(body.moment);  // moment: h x a; force: alpha x h = [h]x^T alpha
  s.c = Mat3{body.mass, 0, 0, 0, body.mass, 0, 0, 0, body.mass};
  s.bias_moment = zero_vec() - body.wrench_moment;
  s.bias_force = zero_vec() - body.wrench_force;
  s.elastic_moment = body.elastic_angular;
  s.elastic_force = body.elastic_linear;
  s.elastic_block = body.elastic_mass;
  for (const ex& f : body.elastic_forcing) s.elastic_bias.push_back(-f);
  return s;
}

/// A rigid body's own terms in its working axes (kane/working_motion.*): its
/// inertia there (numbers), and as the bias minus its applied-plus-inertia
/// wrench, the rate of its momentum with the rest accelerations less the
/// applied forces.
Articulated rigid_terms(Program& program, const TreeBody& body, const FrameStep& from_body,
                        const WorkingMotion& m) {
  const WorkingInertia inertia = working_inertia(body.mass, body.moment, body.second, from_body);
  const SpatialForce applied =
      wrench_in_working({body.applied_moment, body.applied_force}, from_body, program);
  const SpatialForce rate = momentum_rate(inertia, m.omega, m.alpha_rest, m.accel_rest, program);
  Articulated s;
  s.a = inertia.second;
  s.b = skew(inertia.moment);
  s.c = Mat3{body.mass, 0, 0, 0, body.mass, 0, 0, 0, body.mass};
  s.bias_moment = rate.moment - applied.moment;
  s.bias_force = rate.force - applied.force;
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
void drop_joint_direction(Articulated& passed, JointTerms& terms, const Vec3& axis,
                          const kinematics::JointModel& model) {
  const int k = coordinate_of(axis);
  if (k < 0) return;
  Mat3& diagonal = model.part(passed.a, passed.c);
  for (int j = 0; j < 3; ++j) {
    diagonal[3 * k + j] = diagonal[3 * j + k] = 0;
    passed.b[model.part(3 * k + j, 3 * j + k)] = 0;  // B's row k for a turn, column k for a slide
  }
  model.part(terms.w_moment, terms.w_force)[k] = axis[k];
}

/// A child's articulated inertia `moved` (about the parent's origin, parent
/// axes) on a node of the flexible parent: its motion there is the parent's
/// plus Phi eta_ddot, Phi's columns the node's twists (w_k, v_k), so it adds
/// I Phi to the parent's elastic columns, Phi^T I Phi to its elastic block
/// and Phi^T p to its elastic bias.
void add_on_node(Program& program, Articulated& parent, const Articulated& moved,
                 const kinematics::BodyState& child) {
  const std::size_t n = child.node_partial_angular.size();
  const std::size_t m = parent.elastic_bias.size();
  std::vector<Vec3> moment(n), force(n);
  for (std::size_t l = 0; l < n; ++l) {
    const Vec3& w = child.node_partial_angular[l];
    const Vec3& v = child.node_partial_linear[l];
    moment[l] = named(program, mul(moved.a, w) + mul(moved.b, v));
    force[l] = named(program, mul_transposed(moved.b, w) + mul(moved.c, v));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& w = child.node_partial_angular[k];
    const Vec3& v = child.node_partial_linear[k];
    for (std::size_t l = 0; l < n; ++l)
      parent.elastic_block[k * m + l] += dot(w, moment[l]) + dot(v, force[l]);
    parent.elastic_bias[k] += dot(w, moved.bias_moment) + dot(v, moved.bias_force);
    parent.elastic_moment[k] = parent.elastic_moment[k] + moment[k];
    parent.elastic_force[k] = parent.elastic_force[k] + force[k];
  }
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
  Articulated r;
  r.a = named_symmetric(program, x.a);
  r.b = named(program, x.b);
  r.c = named_symmetric(program, x.c);
  r.bias_moment = named(program, x.bias_moment);
  r.bias_force = named(program, x.bias_force);
  const std::size_t m = x.elastic_bias.size();
  r.elastic_block.assign(m * m, 0);
  for (std::size_t k = 0; k < m; ++k) {
    r.elastic_moment.push_back(named(program, x.elastic_moment[k]));
    r.elastic_force.push_back(named(program, x.elastic_force[k]));
    r.elastic_bias.push_back(program.define(x.elastic_bias[k]));
    for (std::size_t l = k; l < m; ++l)
      r.elastic_block[k * m + l] = r.elastic_block[l * m + k] = program.define(x.elastic_block[k * m + l]);
  }
  return r;
}

/// Solves for a flexible body's local speeds (elastic, then its joint's):
/// factors D, forms V, W, g, and leaves in `passed` the top 6 x 6 of
/// I^A - U D^-1 U^T and p^A + U D^-1 (Q - S^T p^A), elastic parts cleared.
/// Returns the first speed whose pivot is 0 in every state, or -1.
int eliminate_block(Program& program, Articulated& passed, const kinematics::JointFrame& joint,
                    int elastic_first, const std::vector<ex>& joint_forces, BlockTerms& t,
                    RecursiveDynamics& out) {
  const int m = static_cast<int>(passed.elastic_bias.size());
  const int n = m + (joint.speed >= 0 ? 1 : 0);
  // U's columns: top part (moment, force) and D's column, Q - S^T p.
  std::vector<Vec3> top_moment(n), top_force(n);
  std::vector<ex> d(n * n), residual(n);
  for (int k = 0; k < m; ++k) {
    t.speeds.push_back(elastic_first + k);
    top_moment[k] = passed.elastic_moment[k];
    top_force[k] = passed.elastic_force[k];
    for (int l = 0; l < m; ++l) d[k * n + l] = passed.elastic_block[k * m + l];
    residual[k] = joint_forces[elastic_first + k] - passed.elastic_bias[k];
  }
  if (joint.speed >= 0) {
    const Vec3& axis = joint.axis;
    t.speeds.push_back(joint.speed);
    const auto [u_moment, u_force] = joint.model.inertia_column(passed.a, passed.b, passed.c, axis);
    top_moment[m] = named(program, u_moment);
    top_force[m] = named(program, u_force);
    for (int k = 0; k < m; ++k)
      d[k * n + m] = d[m * n + k] =
          program.define(joint.model.force_of(axis, passed.elastic_moment[k], passed.elastic_force[k]));
    d[m * n + m] = program.define(joint.model.force_of(axis, top_moment[m], top_force[m]));
    residual[m] =
        joint_forces[joint.speed] - joint.model.force_of(axis, passed.bias_moment, passed.bias_force);
  }
  // LDL^T, and V = L^-1 U^T, z = L^-1 residual, column by column.
  t.lower.assign(n * n, 0);
  std::vector<ex> pivot(n), zs(n);
  std::vector<Vec3> v_moment(n), v_force(n);
  for (int j = 0; j < n; ++j) {
    ex dj = d[j * n + j];
    Vec3 vm = top_moment[j], vf = top_force[j];
    ex z = residual[j];
    for (int p = 0; p < j; ++p) {
      const ex& l = t.lower[j * n + p];
      dj -= l * l * pivot[p];
      vm = vm - l * v_moment[p];
      vf = vf - l * v_force[p];
      z -= l * zs[p];
    }
    pivot[j] = program.define(dj);
    if (pivot[j].is_zero()) return t.speeds[j];
    const ex inverse = program.define(1 / pivot[j]);
    v_moment[j] = named(program, vm);
    v_force[j] = named(program, vf);
    zs[j] = program.define(z);
    t.w_moment.push_back(named(program, inverse * v_moment[j]));
    t.w_force.push_back(named(program, inverse * v_force[j]));
    t.residual_over_pivot.push_back(program.define(inverse * zs[j]));
    t.lower[j * n + j] = 1;
    for (int i = j + 1; i < n; ++i) {
      ex dij = d[i * n + j];
      for (int p = 0; p < j; ++p) dij -= t.lower[i * n + p] * t.lower[j * n + p] * pivot[p];
      t.lower[i * n + j] = program.define(inverse * dij);
    }
    out.pivots[t.speeds[j]] = pivot[j];
    out.pivot_order.push_back(t.speeds[j]);
  }
  // I^A - sum_j V_j W_j^T (symmetric) and p^A + sum_j g_j V_j.
  for (int j = 0; j < n; ++j) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        passed.b[3 * r + c] -= v_moment[j][r] * t.w_force[j][c];
        if (c < r) continue;
        passed.a[3 * r + c] -= v_moment[j][r] * t.w_moment[j][c];
        passed.c[3 * r + c] -= v_force[j][r] * t.w_force[j][c];
        passed.a[3 * c + r] = passed.a[3 * r + c];
        passed.c[3 * c + r] = passed.c[3 * r + c];
      }
    passed.bias_moment = passed.bias_moment + t.residual_over_pivot[j] * v_moment[j];
    passed.bias_force = passed.bias_force + t.residual_over_pivot[j] * v_force[j];
  }
  passed.elastic_moment.clear();
  passed.elastic_force.clear();
  passed.elastic_block.clear();
  passed.elastic_bias.clear();
  return -1;
}

/// One joint's speed eliminated from its body's articulated inertia
/// `passed` (working axes): U = I^A S, D = S^T U, W = U / D, and, if it has
/// a parent, I^A - U W^T and p^A + U (Q - S^T p^A) / D passed on. False if
/// D is the number 0.
bool eliminate_joint(Program& program, Articulated& passed, const kinematics::JointFrame& joint,
                     const Vec3& axis, const std::vector<ex>& joint_forces, bool has_parent, JointTerms& t,
                     RecursiveDynamics& out) {
  const int s = joint.speed;
  const auto [u_moment, u_force] = joint.model.inertia_column(passed.a, passed.b, passed.c, axis);
  t.u_moment = named(program, u_moment);
  t.u_force = named(program, u_force);
  const ex pivot = program.define(joint.model.force_of(axis, t.u_moment, t.u_force));
  if (pivot.is_zero()) return false;
  const ex inverse = program.define(1 / pivot);
  const ex residual = joint_forces[s] - joint.model.force_of(axis, passed.bias_moment, passed.bias_force);
  t.w_moment = named(program, inverse * t.u_moment);
  t.w_force = named(program, inverse * t.u_force);
  t.residual_over_pivot = program.define(inverse * residual);
  out.pivots[s] = pivot;
  out.pivot_order.push_back(s);
  if (!has_parent) return true;  // nothing passed to the ground
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
  drop_joint_direction(passed, t, axis, joint.model);
  return true;
}

/// The local accelerations of a flexible body moving with (angular, linear):
/// y_j = g_j - W_j . a, then x = L^-T y; by local speed.
std::vector<ex> block_accelerations(Program& program, const BlockTerms& t, const Vec3& angular,
                                    const Vec3& linear) {
  const int n = static_cast<int>(t.speeds.size());
  std::vector<ex> x(n);
  for (int j = n; j-- > 0;) {
    ex value = t.residual_over_pivot[j] - dot(t.w_moment[j], angular) - dot(t.w_force[j], linear);
    for (int i = j + 1; i < n; ++i) value -= t.lower[i * n + j] * x[i];
    x[j] = program.define(value);
  }
  return x;
}

}  // namespace

RecursiveDynamics articulated_body_dynamics(const kinematics::TreeKinematics& tree,
                                            const std::vector<TreeBody>& bodies,
                                            const std::vector<ex>& joint_forces,
                                            const std::vector<ex>& speeds, Program& program) {
  const auto& states = tree.bodies();
  const std::size_t count = states.size();
  RecursiveDynamics out;
  out.accelerations.assign(joint_forces.size(), 0);
  out.pivots.assign(joint_forces.size(), 0);

  // The recursion works in each body's working frame (its joint axis along z).
  std::vector<bool> flexible(count);
  for (std::size_t i = 0; i < count; ++i) flexible[i] = bodies[i].elastic_first >= 0;
  const std::vector<WorkingFrame> frames = working_frames(tree, flexible, program);
  const std::vector<WorkingMotion> motion = working_motion(tree, frames, flexible, speeds, program);

  // Inward: children come after their parents, so a reverse sweep has every
  // child's share added before its parent is named.
  std::vector<Articulated> sums(count);
  for (std::size_t i = 0; i < count; ++i)
    sums[i] =
        flexible[i] ? own_terms(bodies[i]) : rigid_terms(program, bodies[i], frames[i].from_body, motion[i]);
  std::vector<JointTerms> terms(count);
  std::vector<BlockTerms> blocks(count);
  for (std::size_t i = count; i-- > 0;) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    Articulated passed = named(program, sums[i]);
    if (!passed.elastic_bias.empty()) {
      const int zero =
          eliminate_block(program, passed, joint, bodies[i].elastic_first, joint_forces, blocks[i], out);
      if (zero >= 0) return {{}, {}, {}, zero};
    } else if (joint.speed >= 0) {
      if (!eliminate_joint(program, passed, joint, frames[i].axis, joint_forces, state.parent_state >= 0,
                           terms[i], out))
        return {{}, {}, {}, joint.speed};  // 1/D does not exist
    }
    if (state.parent_state < 0) continue;
    Articulated moved = named(program, passed);
    for (std::size_t k = frames[i].to_parent.size(); k-- > 0;)
      moved = carried(program, moved, frames[i].to_parent[k]);
    add(sums[state.parent_state], moved);
    if (state.node_first >= 0) add_on_node(program, sums[state.parent_state], moved, state);
  }

  // Outward: the accelerations that u_dot gives, the ground's zero.
  std::vector<Vec3> alpha(count, zero_vec()), accel(count, zero_vec());
  for (std::size_t i = 0; i < count; ++i) {
    const kinematics::BodyState& state = states[i];
    const kinematics::JointFrame& joint = tree.joints()[state.joint];
    Vec3 angular = zero_vec(), linear = zero_vec();
    if (state.parent_state >= 0) {
      Vec3 parent_alpha = alpha[state.parent_state], parent_accel = accel[state.parent_state];
      // On a node: the parent's motion there, plus Phi eta_ddot.
      for (std::size_t k = 0; k < state.node_partial_angular.size(); ++k) {
        const ex& eta_ddot = out.accelerations[state.node_first + static_cast<int>(k)];
        parent_alpha = parent_alpha + eta_ddot * state.node_partial_angular[k];
        parent_accel = parent_accel + eta_ddot * state.node_partial_linear[k];
      }
      angular = named(program, parent_alpha);
      linear = named(program, parent_accel);
      carry_outward(frames[i].to_parent, angular, linear, program);
    }
    if (!blocks[i].speeds.empty()) {
      const std::vector<ex> x = block_accelerations(program, blocks[i], angular, linear);
      for (std::size_t j = 0; j < x.size(); ++j) out.accelerations[blocks[i].speeds[j]] = x[j];
      if (joint.speed >= 0) {
        const ex& udot = x.back();
        Vec3& moved = joint.model.part(angular, linear);  // a_i += S u_dot
        moved = named(program, moved + udot * joint.axis);
      }
    } else if (joint.speed >= 0) {
      const JointTerms& t = terms[i];
      const ex udot =
          program.define(t.residual_over_pivot - dot(t.w_moment, angular) - dot(t.w_force, linear));
      out.accelerations[joint.speed] = udot;
      Vec3& moved = joint.model.part(angular, linear);  // a_i += S u_dot
      moved = named(program, moved + udot * frames[i].axis);
    }
    alpha[i] = angular;
    accel[i] = linear;
  }
  return out;
}

}  // namespace kanegen::kane
