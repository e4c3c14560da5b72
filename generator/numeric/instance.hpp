// A model with its parameters given values: every scalar evaluated, names
// resolved to indices, bodies put in an order where parents come first. The
// numeric derivation works on this plain-number form only.
#pragma once

#include <string>
#include <vector>

#include "model/expression_eval.hpp"
#include "model/model.hpp"
#include "numeric/small_matrix.hpp"

namespace kanegen::numeric {

enum class Motion { none, rotation, translation };

struct JointData {
  std::string name;
  int parent = -1;  ///< body index; -1 for the ground
  int child = -1;   ///< body index
  Motion motion = Motion::none;
  Mat<double> origin_rotation;  ///< joint frame in parent axes (URDF rpy)
  Vec<double> origin_position;  ///< joint frame origin in the parent frame
  Vec<double> axis;             ///< unit, joint-frame axes
  int coordinate = -1;          ///< index in q and u; -1 for a fixed joint
  double stiffness = 0, rest = 0, damping = 0;
  bool actuated = false;
};

struct BodyData {
  std::string name;
  int joint = -1;  ///< index of the joint that carries it
  double mass = 0;
  Vec<double> com;      ///< body frame
  Mat<double> inertia;  ///< about the centre of mass, body axes
};

struct ForceData {
  std::string name;
  int body = -1;
  Vec<double> point;  ///< body frame
  Vec<double> force;  ///< world or body axes
  bool body_frame = false;
};

struct OutputData {
  std::string name;
  model::OutputKind kind = model::OutputKind::point_position;
  int body = -1;  ///< -1 for the ground
  Vec<double> point;
  int coordinate = -1;
};

struct Instance {
  std::vector<BodyData> bodies;
  std::vector<JointData> joints;      ///< model order
  std::vector<int> order;             ///< body indices, every parent before its children
  std::vector<int> coordinate_joint;  ///< joint index of each coordinate
  Vec<double> gravity;
  std::vector<ForceData> forces;
  std::vector<OutputData> outputs;

  int coordinates() const { return static_cast<int>(coordinate_joint.size()); }
};

/// Evaluates the model at the given parameter values. Throws
/// std::invalid_argument if a name cannot be resolved or an expression
/// cannot be evaluated (a loaded model has been checked, so only on misuse).
Instance instantiate(const model::Model& model, const model::ParameterValues& parameters);

/// URDF's fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
Mat<double> rotation_from_rpy(double roll, double pitch, double yaw);

}  // namespace kanegen::numeric
