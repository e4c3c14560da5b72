// SPDX-License-Identifier: GPL-2.0-or-later
// The numeric path's view of spherical joints. Its state q has one
// coordinate per speed: a ball's three are a rotation vector phi from the
// joint's base quaternion (JointData::base), and it evaluates at phi = 0.
// The generated kernels take the quaternion itself, its x, y, z at the
// ball's speeds and every w after the other coordinates (the model format's
// layout, docs/model-format.md). These functions go between the two and give
// the quaternion's rate, each written here from the quaternion algebra, not
// taken from the generator.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "numeric/instance.hpp"

namespace kanegen::numeric {

/// The names of the generated kernels' coordinates (nq = nu + balls): the
/// numeric path's, then each ball's quaternion w, `<joint>_qw`.
inline std::vector<std::string> kernel_coordinate_names(const Instance& m) {
  std::vector<std::string> names = m.coordinate_names;
  for (int k : m.ball_joints) names.push_back(m.joints[k].name + "_qw");
  return names;
}

/// The generated kernels' q (nq = nu + balls) of the numeric state q (nu),
/// with every ball at its base (phi = 0 is required).
inline std::vector<double> kernel_coordinates(const Instance& m, const std::vector<double>& q) {
  std::vector<double> out = q;
  for (int k : m.ball_joints) {
    const JointData& j = m.joints[k];
    for (int c = 0; c < 3; ++c) {
      if (q.at(j.coordinate + c) != 0.0)
        throw std::invalid_argument("kernel_coordinates: a ball's rotation vector is not zero");
      out[j.coordinate + c] = j.base[1 + c];
    }
  }
  for (int k : m.ball_joints) out.push_back(m.joints[k].base[0]);
  return out;
}

/// Sets every ball's base to the (normalised) quaternion of the kernels'
/// coordinates `kernel_q` (nq) and returns the numeric q (nu, phi = 0).
inline std::vector<double> take_kernel_coordinates(Instance& m, const double* kernel_q) {
  const int n = m.coordinates();
  std::vector<double> q(kernel_q, kernel_q + n);
  int w = n;
  for (int k : m.ball_joints) {
    JointData& j = m.joints[k];
    double wxyz[4] = {kernel_q[w++], kernel_q[j.coordinate], kernel_q[j.coordinate + 1],
                      kernel_q[j.coordinate + 2]};
    const double length =
        std::sqrt(wxyz[0] * wxyz[0] + wxyz[1] * wxyz[1] + wxyz[2] * wxyz[2] + wxyz[3] * wxyz[3]);
    if (!(length > 0)) throw std::invalid_argument("take_kernel_coordinates: a quaternion of length 0");
    for (int c = 0; c < 4; ++c) j.base[c] = wxyz[c] / length;
    for (int c = 0; c < 3; ++c) q[j.coordinate + c] = 0.0;
  }
  return q;
}

/// The kernels' q_dot (nq) at their q (nq) and speeds u (nu): u for every
/// coordinate that has a speed; a ball's quaternion turns with the angular
/// velocity u in its child's axes, q_dot = 1/2 q (0, u) (Hamilton product).
inline void kernel_coordinate_rates(const Instance& m, const double* kernel_q, const double* u,
                                    double* qdot) {
  const int n = m.coordinates();
  for (int i = 0; i < n; ++i) qdot[i] = u[i];
  int w = n;
  for (int k : m.ball_joints) {
    const int c = m.joints[k].coordinate;
    const double s = kernel_q[w], x = kernel_q[c], y = kernel_q[c + 1], z = kernel_q[c + 2];
    const double a = u[c], b = u[c + 1], d = u[c + 2];
    qdot[w++] = -0.5 * (x * a + y * b + z * d);
    qdot[c] = 0.5 * (s * a + y * d - z * b);
    qdot[c + 1] = 0.5 * (s * b + z * a - x * d);
    qdot[c + 2] = 0.5 * (s * d + x * b - y * a);
  }
}

}  // namespace kanegen::numeric
