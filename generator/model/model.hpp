// The mechanism as plain data: what the model file says, checked and
// normalised, with no algorithm attached (as Pinocchio's Model and MuJoCo's
// mjModel). Loaders fill it; the symbolic stages only read it.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace kanegen::model {

/// A scalar quantity of the model. Either a plain number (folded into the
/// generated code) or an expression over named parameters ("m1", "0.5*l1"),
/// which stays symbolic and can be changed at run time through Params.
struct Scalar {
  bool is_literal = true;
  double value = 0.0;  ///< the number when is_literal
  std::string text;    ///< the expression when !is_literal
  std::string where;   ///< JSON pointer or URDF element, for error messages

  static Scalar number(double v, std::string where_ = {}) {
    Scalar s;
    s.value = v;
    s.where = std::move(where_);
    return s;
  }
  static Scalar expression(std::string t, std::string where_ = {}) {
    Scalar s;
    s.is_literal = false;
    s.text = std::move(t);
    s.where = std::move(where_);
    return s;
  }
};

using Vec3 = std::array<Scalar, 3>;

/// A named parameter; its default value is what Params starts with.
struct Parameter {
  std::string name;
  double value = 0.0;
  std::string where;
};

/// A rigid body. Frame: the body frame is the child frame of the joint that
/// carries it. Inertia is about the centre of mass, in body-frame axes.
struct Body {
  std::string name;
  Scalar mass;
  Vec3 com;                       ///< centre of mass in the body frame
  std::array<Scalar, 6> inertia;  ///< ixx, iyy, izz, ixy, ixz, iyz
  std::string where;
};

enum class JointType { revolute, continuous, prismatic, fixed };

/// A joint between a parent body (or the ground) and a child body.
/// The child frame is the parent frame moved by origin (xyz, then rpy as
/// URDF: R = Rz(yaw) Ry(pitch) Rx(roll)) and then by the joint motion
/// along or about `axis` (expressed in the joint frame, unit length).
struct Joint {
  std::string name;
  JointType type = JointType::revolute;
  std::string parent;  ///< body name, or Model::ground
  std::string child;   ///< body name
  Vec3 origin_xyz;
  Vec3 origin_rpy;
  std::array<double, 3> axis{0.0, 0.0, 1.0};
  Scalar spring_stiffness;  ///< generalized spring: -k (q - rest)
  Scalar spring_rest;
  Scalar damping;        ///< generalized damper: -c u
  bool actuated = true;  ///< has an input torque/force tau
  double q0 = 0.0;       ///< initial coordinate
  double u0 = 0.0;       ///< initial speed
  std::string where;

  bool moves() const { return type != JointType::fixed; }
};

enum class ForceFrame { world, body };

/// A constant force applied at a point fixed in a body.
struct PointForce {
  std::string name;
  std::string body;
  Vec3 point;  ///< in the body frame
  Vec3 force;  ///< in `frame` axes
  ForceFrame frame = ForceFrame::world;
  std::string where;
};

enum class OutputKind { point_position, joint_coordinate, joint_speed };

/// A named quantity written by `simulate`. A point position expands to the
/// three columns NAME.x, NAME.y, NAME.z (world frame).
struct Output {
  std::string name;
  OutputKind kind = OutputKind::point_position;
  std::string body;   ///< for point_position
  Vec3 point;         ///< for point_position, in the body frame
  std::string joint;  ///< for joint_coordinate / joint_speed
  std::string where;
};

struct Model {
  std::string name;               ///< a C++ identifier; names the namespace and files
  std::string source_file;        ///< the file it was loaded from
  std::string ground = "ground";  ///< the fixed body's name (URDF: the root link)

  std::vector<Parameter> parameters;
  std::vector<Body> bodies;
  std::vector<Joint> joints;  ///< file order; moving joints give the coordinates in this order
  Vec3 gravity;               ///< world frame, m/s^2
  std::vector<PointForce> forces;
  std::vector<Output> outputs;
};

}  // namespace kanegen::model
