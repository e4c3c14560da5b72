// The position functions: world pose of every body as a function of the
// coordinates, written once over the scalar type. With S = double they give
// positions; with S = Dual<double> seeded along e_r, the partial velocities
// (u = q_dot); with S = Dual<Dual<double>> seeded along u, velocities and the
// accelerations at u_dot = 0. Nothing here knows about derivatives.
#pragma once

#include <vector>

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

/// World poses of all bodies (indexed like Instance::bodies) at coordinates q.
/// Child frame = parent frame, moved by the joint origin (xyz, then rpy),
/// then by the joint motion about or along the axis in that joint frame.
template <class S>
std::vector<Pose<S>> body_poses(const Instance& m, const S* q) {
  std::vector<Pose<S>> poses(m.bodies.size());
  const Pose<S> ground{identity<S>(), Vec<S>{S(0.0), S(0.0), S(0.0)}};
  for (const int b : m.order) {
    const JointData& j = m.joints[m.bodies[b].joint];
    const Pose<S>& parent = j.parent < 0 ? ground : poses[j.parent];
    Pose<S>& pose = poses[b];
    pose.rotation = mul(parent.rotation, j.origin_rotation);
    pose.origin = add(parent.origin, mul(parent.rotation, j.origin_position));
    if (j.motion == Motion::rotation) {
      pose.rotation = mul(pose.rotation, rotation_about(j.axis, q[j.coordinate]));
    } else if (j.motion == Motion::translation) {
      const Vec<S> slide{j.axis[0] * q[j.coordinate], j.axis[1] * q[j.coordinate],
                         j.axis[2] * q[j.coordinate]};
      pose.origin = add(pose.origin, mul(pose.rotation, slide));
    }
  }
  return poses;
}

/// World position of a point given in body axes (body -1: the ground).
template <class S>
Vec<S> point_position(const std::vector<Pose<S>>& poses, int body, const Vec<double>& local) {
  if (body < 0) return cast<S>(local);
  return add(poses[body].origin, mul(poses[body].rotation, local));
}

}  // namespace kanegen::numeric
