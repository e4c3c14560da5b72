// Symbolic kinematics of a rigid tree, in world axes: the pose, angular
// velocity and the velocity-independent-of-u_dot ("rest") accelerations of
// every body, and the partial velocities of points as the coefficients of
// the generalized speeds (u = q_dot). Built by the outward recursion
// w_i = w_p + a_k u_k, never by differentiating expanded expressions.
#pragma once

#include <vector>

#include "model/model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kinematics {

using symbolic::Mat3;
using symbolic::Vec3;

/// A joint placed in the world: its axis a_k and the origin o_k of its child
/// frame (on the axis for a revolute joint).
struct JointFrame {
  int speed = -1;  ///< index of its generalized speed; -1 for a fixed joint
  bool prismatic = false;
  Vec3 axis;    ///< a_k, world axes
  Vec3 origin;  ///< o_k, world
};

struct BodyState {
  int body = -1;         ///< index in Model::bodies
  int parent_state = -1;  ///< index in TreeKinematics::bodies; -1 for the ground
  int joint = -1;        ///< index in Model::joints of the joint that carries it
  Mat3 rotation;         ///< body axes -> world
  Vec3 origin;           ///< body frame origin, world
  Vec3 omega;            ///< angular velocity
  Vec3 velocity;         ///< velocity of the origin
  Vec3 alpha_rest;       ///< angular acceleration with u_dot = 0
  Vec3 accel_rest;       ///< acceleration of the origin with u_dot = 0
  std::vector<int> path;  ///< moving joints from the ground to this body (Model::joints indices)
};

class TreeKinematics {
 public:
  TreeKinematics(const model::Model& model, const symbolic::Variables& vars, symbolic::Program& program);

  const std::vector<BodyState>& bodies() const { return bodies_; }  ///< parents before children
  const std::vector<JointFrame>& joints() const { return joints_; }  ///< Model::joints order
  /// Index in bodies() of the named body, or -1 for the ground.
  int state_of(const std::string& body_name) const;

  /// World position of a point given in body axes.
  Vec3 point(const BodyState& b, const Vec3& local) const;
  /// Velocity and rest acceleration of a point fixed in the body at world position p.
  Vec3 point_velocity(const BodyState& b, const Vec3& p) const;
  Vec3 point_accel_rest(const BodyState& b, const Vec3& p) const;
  /// The partial velocities of speed r: the partial angular velocity w_r and
  /// the partial velocity v_r of the body point passing the world origin, so
  /// that the partial velocity of any point p of a body on r's subtree is
  /// v_r + w_r x p (and zero off the subtree). Revolute: (a_k, o_k x a_k);
  /// prismatic: (0, a_k).
  void partial_velocities(int r, Vec3& w_r, Vec3& v_r) const;

 private:
  const model::Model& model_;
  symbolic::Program& program_;
  std::vector<BodyState> bodies_;
  std::vector<JointFrame> joints_;
  std::vector<int> joint_of_speed_;
};

/// URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll).
Mat3 rotation_rpy(const GiNaC::ex& roll, const GiNaC::ex& pitch, const GiNaC::ex& yaw);
/// Rotation by angle about a unit axis (Rodrigues).
Mat3 rotation_about(const Vec3& axis, const GiNaC::ex& angle);

}  // namespace kanegen::kinematics
