// SPDX-License-Identifier: GPL-2.0-or-later
// Symbolic kinematics of a rigid tree in body frames (each quantity in the
// axes of the body it belongs to, as in Featherstone's recursions): joint
// rotations stay sparse and constant offsets keep their zeros, which keeps the
// generated code short. World poses are kept too, for outputs and energies.
// Everything is built by the outward recursion w_i = E_i w_p + a_k u_k, never
// by differentiating expanded expressions.
#pragma once

#include <Eigen/Dense>
#include <map>
#include <vector>

#include "kinematics/joint_model.hpp"
#include "model/model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kinematics {

using symbolic::Mat3;
using symbolic::Vec3;

/// A joint: its speed index, its type's model and its axis in the child
/// body's frame. The child frame origin lies on a revolute joint's axis, so
/// the partial angular and linear velocities of the child origin for the
/// joint's own speed are its column of S, (a_k, 0) (a turn) or (0, a_k) (a
/// slide), in child axes.
struct JointFrame {
  int speed = -1;         ///< index of its (first) generalized speed; -1 for a fixed joint
  JointModel model;       ///< what its type does (kinematics/joint_model.hpp)
  Vec3 axis;              ///< a_k, child axes (unit)
  GiNaC::ex coordinate;   ///< q_k (a moving joint's; a spherical joint's quaternion x)
  int quaternion_w = -1;  ///< a spherical joint's: the index in q of its quaternion's w

  /// The joint's speeds, speed .. speed + speeds() - 1 (none for a fixed joint).
  int speeds() const { return model.speeds(); }
  /// Column c of S in child axes: the axis, or a spherical joint's child axis c.
  Vec3 column(int c) const { return model.column_axis(axis, c); }
  /// The joint frame in the parent's, as the model gives it (before a node's
  /// motion): origin (parent axes) and rotation (joint axes -> parent axes).
  Vec3 origin_xyz;
  Mat3 origin_rotation;
  bool on_node = false;  ///< on a node of a flexible parent
};

/// A joint on a node of a flexible parent: the joint frame is the node's
/// frame, moved by the node's elastic displacement and turned by its small
/// rotation theta = C eta, made exact as Rx(theta_x) Ry(theta_y) Rz(theta_z)
/// (node_turn; a planar beam turns about z only), so that the frame's angular
/// velocity is that rotation's and the model stays conservative. With
/// geometric stiffening in modes the node is also carried back by the beam's
/// foreshortening, f_a = -1/2 eta^T H_a eta (fem/foreshortening.hpp), exactly.
struct NodeAttachment {
  Eigen::Vector3d position;     ///< undeformed, parent link frame
  Eigen::MatrixXd translation;  ///< 3 x n: displacement = translation eta (+ f)
  Eigen::MatrixXd rotation;     ///< 3 x n: small rotation theta = rotation eta, link axes
  int first = 0;                ///< the parent's first elastic coordinate in q and u
  /// n x n each: H_a at the node; empty without foreshortening.
  std::vector<Eigen::MatrixXd> shortening;
};

struct BodyState {
  int body = -1;          ///< index in Model::bodies
  int parent_state = -1;  ///< index in TreeKinematics::bodies; -1 for the ground
  int joint = -1;         ///< index in Model::joints of the joint that carries it
  Mat3 to_child;          ///< E_i: parent axes -> child axes
  Vec3 offset;            ///< r_i: parent origin -> child origin, parent axes
  Mat3 rotation;          ///< R_0i: body axes -> world
  Vec3 origin;            ///< body frame origin, world
  Vec3 omega;             ///< angular velocity, body axes
  Vec3 velocity;          ///< velocity of the origin, body axes
  Vec3 alpha_rest;        ///< angular acceleration with u_dot = 0, body axes
  Vec3 accel_rest;  ///< acceleration of the origin with u_dot = 0, minus the base's (gravity), body axes
  std::vector<int> path;  ///< moving joints from the ground to this body (Model::joints indices)
  /// On a node of a flexible parent: the parent's elastic speeds from
  /// node_first on move this body's subtree rigidly, with the partial
  /// angular velocity and partial velocity at the parent's origin, parent axes.
  int node_first = -1;
  std::vector<Vec3> node_partial_angular, node_partial_linear;
};

class TreeKinematics {
 public:
  /// base_acceleration: acceleration given to the ground, world axes; -g
  /// carries gravity into every body's rest acceleration.
  /// attachments: by joint index, the joints on nodes of flexible parents.
  TreeKinematics(const model::Model& model, const symbolic::Variables& vars, symbolic::Program& program,
                 const Vec3& base_acceleration, const std::map<int, NodeAttachment>& attachments = {});

  const std::vector<BodyState>& bodies() const { return bodies_; }   ///< parents before children
  const std::vector<JointFrame>& joints() const { return joints_; }  ///< Model::joints order
  /// Index in bodies() of the named body, or -1 for the ground.
  int state_of(const std::string& body_name) const;

  /// World position of a point given in body axes.
  Vec3 world_point(const BodyState& b, const Vec3& local) const;

 private:
  /// Joint k's child body from its parent's state p: its frame, velocities
  /// and rest accelerations; sets joint k's frame.
  BodyState place(std::size_t k, int parent, const BodyState& p, const symbolic::Variables& vars,
                  const NodeAttachment* attachment);

  const model::Model& model_;
  symbolic::Program& program_;
  std::vector<BodyState> bodies_;
  std::vector<JointFrame> joints_;
};

/// v, named if `turn` has a constant entry other than 0 and +-1, for turn v:
/// GiNaC distributes such a constant over every sum in v, which would repeat
/// the sum's terms in each row instead of sharing them.
Vec3 named_before_turn(symbolic::Program& program, const Mat3& turn, const Vec3& v);

/// URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll).
Mat3 rotation_rpy(const GiNaC::ex& roll, const GiNaC::ex& pitch, const GiNaC::ex& yaw);
/// Rotation by angle about a unit axis (Rodrigues).
Mat3 rotation_about(const Vec3& axis, const GiNaC::ex& angle);
/// A node's small rotation theta made exact: Rx(theta_x) Ry(theta_y) Rz(theta_z).
Mat3 node_turn(const std::array<GiNaC::ex, 3>& theta);

}  // namespace kanegen::kinematics
