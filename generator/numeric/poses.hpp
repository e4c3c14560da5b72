// SPDX-License-Identifier: GPL-2.0-or-later
// The position functions: world pose of every body as a function of the
// coordinates, written once over the scalar type. With S = double they give
// positions; with S = Dual<double> seeded along e_r, the partial velocities
// (u = q_dot); with S = Dual<Dual<double>> seeded along u, velocities and the
// accelerations at u_dot = 0. Nothing here knows about derivatives.
#pragma once

#include <stdexcept>
#include <vector>

#include "numeric/beam.hpp"
#include "numeric/instance.hpp"
#include "numeric/small_matrix.hpp"

namespace kanegen::numeric {

template <class S>
struct Pose {
  Mat<S> rotation;  ///< body axes -> world
  Vec<S> origin;    ///< body frame origin, world
};

/// Rotation by `angle` about the unit `axis` (Rodrigues):
/// R = cos I + sin [a]x + (1 - cos) a a^T.
template <class S>
Mat<S> rotation_about(const Vec<double>& a, const S& angle) {
  using std::cos;
  using std::sin;
  const S c = cos(angle), s = sin(angle);
  const S k = 1.0 - c;
  return {c + k * (a[0] * a[0]),        k * (a[0] * a[1]) - s * a[2], k * (a[0] * a[2]) + s * a[1],
          k * (a[1] * a[0]) + s * a[2], c + k * (a[1] * a[1]),        k * (a[1] * a[2]) - s * a[0],
          k * (a[2] * a[0]) - s * a[1], k * (a[2] * a[1]) + s * a[0], c + k * (a[2] * a[2])};
}

/// A ball's turn from its base quaternion (w, x, y, z) by the rotation
/// vector phi: R(base) (I + [phi]x + 1/2 [phi]x^2), exp([phi]x) to second
/// order, exact with its first and second derivatives at phi = 0, where the
/// numeric path evaluates it (Motion::ball).
template <class S>
Mat<S> ball_turn(const std::array<double, 4>& base, const S* phi) {
  const double w = base[0], x = base[1], y = base[2], z = base[3];
  const Mat<double> r0{1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                       2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                       2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  const Mat<S> skew{S(0.0), -phi[2], phi[1], phi[2], S(0.0), -phi[0], -phi[1], phi[0], S(0.0)};
  const Mat<S> square = mul(skew, skew);
  Mat<S> local = identity<S>();
  for (int k = 0; k < 9; ++k) local[k] = local[k] + skew[k] + 0.5 * square[k];
  return mul(r0, local);
}

/// A node's small rotation theta made exact, Rx(theta_x) Ry(theta_y) Rz(theta_z)
/// (a planar beam's node turns about z only).
template <class S>
Mat<S> node_turn(const Vec<S>& theta) {
  const Vec<double> axes[3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  Mat<S> turn = identity<S>();
  for (int a = 0; a < 3; ++a) turn = mul(turn, rotation_about(axes[a], theta[a]));
  return turn;
}

/// The nodal dofs of every flexible body at coordinates q (empty for rigid bodies).
template <class S>
std::vector<std::vector<S>> all_beam_dofs(const Instance& m, const S* q) {
  std::vector<std::vector<S>> dofs(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (m.bodies[b].elastic) dofs[b] = beam_dofs(*m.bodies[b].elastic, q + m.bodies[b].elastic_first);
  return dofs;
}

/// second_order of every flexible body's dofs (all_beam_dofs), once per state
/// (empty for rigid bodies).
template <class S>
std::vector<SecondOrder<S>> all_second_order(const Instance& m, const std::vector<std::vector<S>>& dofs) {
  std::vector<SecondOrder<S>> second(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (m.bodies[b].elastic) second[b] = second_order(*m.bodies[b].elastic, dofs[b]);
  return second;
}

/// World poses of all bodies (indexed like Instance::bodies) at coordinates q
/// (`dofs`: all_beam_dofs at q, `second`: all_second_order of them). Child frame = parent frame, moved by the
/// joint origin (xyz, then rpy), then by the joint motion about or along the
/// axis in that joint frame. A joint on a node of a flexible parent starts
/// from the node's frame instead: the parent frame moved to the displaced
/// node and turned by the node's rotation (exactly, node_turn).
template <class S>
std::vector<Pose<S>> body_poses(const Instance& m, const S* q, const std::vector<std::vector<S>>& dofs,
                                const std::vector<SecondOrder<S>>& second) {
  std::vector<Pose<S>> poses(m.bodies.size());
  const Pose<S> ground{identity<S>(), Vec<S>{S(0.0), S(0.0), S(0.0)}};
  for (const int b : m.order) {
    const JointData& j = m.joints[m.bodies[b].joint];
    Pose<S> parent = j.parent < 0 ? ground : poses[j.parent];
    if (j.parent_node >= 0) {
      const FlexibleData& beam = *m.bodies[j.parent].elastic;
      parent.origin =
          add(parent.origin,
              mul(parent.rotation, displaced_node(beam, dofs[j.parent], second[j.parent], j.parent_node)));
      parent.rotation = mul(parent.rotation, node_turn(node_rotation(beam, dofs[j.parent], j.parent_node)));
    }
    Pose<S>& pose = poses[b];
    pose.rotation = mul(parent.rotation, j.origin_rotation);
    pose.origin = add(parent.origin, mul(parent.rotation, j.origin_position));
    if (j.motion == Motion::rotation) {
      pose.rotation = mul(pose.rotation, rotation_about(j.axis, q[j.coordinate]));
    } else if (j.motion == Motion::ball) {
      pose.rotation = mul(pose.rotation, ball_turn(j.base, q + j.coordinate));
    } else if (j.motion == Motion::translation) {
      const Vec<S> slide{j.axis[0] * q[j.coordinate], j.axis[1] * q[j.coordinate],
                         j.axis[2] * q[j.coordinate]};
      pose.origin = add(pose.origin, mul(pose.rotation, slide));
    }
  }
  return poses;
}

/// The same, for a model without node attachments or when the dofs are not needed elsewhere.
template <class S>
std::vector<Pose<S>> body_poses(const Instance& m, const S* q) {
  const std::vector<std::vector<S>> dofs = all_beam_dofs(m, q);
  return body_poses(m, q, dofs, all_second_order(m, dofs));
}

/// World position of a point given in body axes (body -1: the ground).
template <class S>
Vec<S> point_position(const std::vector<Pose<S>>& poses, int body, const Vec<double>& local) {
  if (body < 0) return cast<S>(local);
  return add(poses[body].origin, mul(poses[body].rotation, local));
}

}  // namespace kanegen::numeric
