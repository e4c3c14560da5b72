// SPDX-License-Identifier: GPL-2.0-or-later
// The closed loops as the numeric path sees them (docs/closed-loops.md): the
// closure equations Phi(q) from the world poses of poses.hpp, written once
// over the scalar type like the poses, so that dual numbers give their
// Jacobian C = dPhi/dq (seeded along e_r) and the bias gamma = -(dC/dt) u
// (the second derivative of Phi along u: d2/ds2 Phi(q + s u) = (dC/dt) u).
// Then the index-1 equations M udot = f + C^T lambda, C udot = gamma.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "numeric/beam.hpp"
#include "numeric/instance.hpp"
#include "numeric/poses.hpp"
#include "numeric/small_matrix.hpp"

namespace kanegen::numeric {

/// Two unit vectors e1, e2 across the unit n, (e1, e2, n) right-handed: e1
/// is the coordinate axis least aligned with n (the first of equals) made
/// normal to n, e2 = n x e1. For n = z they are x and y. This is the
/// documented basis of the rows across an axis (docs/model-format.md#loops).
inline std::array<Vec<double>, 2> across(const Vec<double>& n) {
  int helper = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[helper])) helper = k;
  Vec<double> e1{0.0, 0.0, 0.0};
  e1[helper] = 1.0;
  e1 = sub(e1, scale(n, n[helper]));
  e1 = scale(e1, 1.0 / std::sqrt(dot(e1, e1)));
  return {e1, cross(n, e1)};
}

/// The world position of one side of a loop: a body point, a node of a
/// flexible body (moving with its deformation) or a ground point.
template <class S>
Vec<S> loop_point(const Instance& m, const std::vector<Pose<S>>& poses,
                  const std::vector<std::vector<S>>& dofs, const std::vector<SecondOrder<S>>& second,
                  int body, int node, const Vec<double>& point) {
  if (body < 0) return cast<S>(point);
  if (node < 0) return point_position(poses, body, point);
  const FlexibleData& f = *m.bodies[body].elastic;
  const Vec<S> local = displaced_node(f, dofs[body], second[body], node);
  return add(poses[body].origin, mul(poses[body].rotation, local));
}

/// Phi at coordinates q: every loop's rows in model order, as LoopData::rows names them.
template <class S>
std::vector<S> loop_residuals(const Instance& m, const S* q) {
  const std::vector<std::vector<S>> dofs = all_beam_dofs(m, q);
  const std::vector<SecondOrder<S>> second = all_second_order(m, dofs);
  const std::vector<Pose<S>> poses = body_poses(m, q, dofs, second);
  // A side's frame: the ground, a body, or a node of a flexible body (turned by its rotation).
  const auto rotation = [&](int body, int node) {
    if (body < 0) return identity<S>();
    if (node < 0) return poses[body].rotation;
    const FlexibleData& f = *m.bodies[body].elastic;
    return mul(poses[body].rotation, node_turn(node_rotation(f, dofs[body], node)));
  };
  std::vector<S> phi;
  for (const LoopData& l : m.loops) {
    const Vec<S> gap = sub(loop_point(m, poses, dofs, second, l.body, l.node, l.point),
                           loop_point(m, poses, dofs, second, l.body2, l.node2, l.point2));
    const std::array<Vec<double>, 2> plane = across(l.axis);
    switch (l.type) {
      case model::LoopType::spherical:
        phi.insert(phi.end(), gap.begin(), gap.end());
        break;
      case model::LoopType::revolute:
        if (l.planar) {
          phi.push_back(dot(plane[0], gap));
          phi.push_back(dot(plane[1], gap));
        } else {
          phi.insert(phi.end(), gap.begin(), gap.end());
          // The hinge axis, in both bodies' frames, kept normal to the second body's e1, e2.
          const Vec<S> hinge = mul(rotation(l.body, l.node), l.axis);
          phi.push_back(dot(hinge, mul(rotation(l.body2, l.node2), plane[0])));
          phi.push_back(dot(hinge, mul(rotation(l.body2, l.node2), plane[1])));
        }
        break;
      case model::LoopType::slider:
        if (l.planar) {
          // Across the line in the x-y plane of the first body: z x axis.
          Vec<double> normal{-l.axis[1], l.axis[0], 0.0};
          normal = scale(normal, 1.0 / std::sqrt(dot(normal, normal)));
          phi.push_back(dot(mul(rotation(l.body, l.node), normal), gap));
        } else {
          phi.push_back(dot(mul(rotation(l.body, l.node), plane[0]), gap));
          phi.push_back(dot(mul(rotation(l.body, l.node), plane[1]), gap));
        }
        break;
    }
  }
  return phi;
}

struct LoopKinematics {
  std::vector<double> phi;       ///< nc
  std::vector<double> jacobian;  ///< nc * n, row-major
  std::vector<double> bias;      ///< nc: gamma = -(dC/dt) u
};

/// Phi, C and gamma at (q, u).
LoopKinematics loop_kinematics(const Instance& m, const std::vector<double>& q, const std::vector<double>& u);

struct ConstrainedSolution {
  bool ok = false;             ///< false: C_f M_ff^-1 C_f^T or M_ff not positive definite
  std::vector<double> udot;    ///< n
  std::vector<double> lambda;  ///< nc
};

/// Solves M udot = f + C^T lambda, C udot = gamma with the prescribed speeds'
/// accelerations imposed (their columns of C moved to the right, their rows
/// of the first equation dropped): M row-major n x n.
ConstrainedSolution solve_constrained(int n, const std::vector<double>& mass_matrix,
                                      const std::vector<double>& forcing, const LoopKinematics& loops,
                                      const std::vector<int>& prescribed,
                                      const std::vector<double>& prescribed_acceleration);

/// Puts (q, u) on the constraint manifold, moving only the coordinates not
/// in `held` (the prescribed ones): least-norm Newton steps on Phi (each at
/// most 0.5 long), then the least-norm correction of the speeds to C u = 0.
/// False (q, u unchanged) if |Phi| does not fall below 1e-12 in 50 steps.
bool project_onto_loops(const Instance& m, const std::vector<int>& held, std::vector<double>& q,
                        std::vector<double>& u);

}  // namespace kanegen::numeric
