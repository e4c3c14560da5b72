// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/joint_expansion.hpp"

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "model/model_error.hpp"

namespace kanegen::model {
namespace {

using Axis = std::array<double, 3>;

Axis cross(const Axis& a, const Axis& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

std::string step_name(const Joint& j, const JointStep& step) {
  return *step.suffix ? j.name + "_" + step.suffix : j.name;
}
std::string frame_name(const Joint& j, const JointStep& step) { return step_name(j, step) + "_frame"; }

/// "J_x, J_y and J_theta": the names a user may give instead of J.
std::string step_names(const Joint& j, const char* conjunction) {
  const JointTypeInfo& info = joint_type_info(j.type);
  std::vector<std::string> names;
  for (int s = 0; s < info.step_count; ++s) names.push_back("'" + step_name(j, info.steps[s]) + "'");
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? std::string(" ") + conjunction + " " : ", ") + names[i];
  return out;
}

/// What a joint of several coordinates cannot carry (yet): a spring,
/// damping, a prescribed motion, an independent coordinate of a loop, a node
/// of a flexible parent.
void check_several_coordinates(const Model& m, const Joint& j) {
  const JointTypeInfo& info = joint_type_info(j.type);
  const std::string type = info.name;
  const auto refuse = [&](const std::string& key, const std::string& what) {
    throw ModelError(m.source_file, j.where + "/" + key, what + " on " + type + " joint '" + j.name + "'",
                     info.compound()
                         ? "remove it (a " + type + " joint carries none), or build the motion from " +
                               step_names(j, "and") + " as separate joints"
                         : "remove it (a " + type + " joint carries none)");
  };
  if (!j.spring_stiffness.is_literal || j.spring_stiffness.value != 0) refuse("spring", "a spring");
  if (!j.damping.is_literal || j.damping.value != 0) refuse("damping", "damping");
  if (j.is_prescribed()) refuse("prescribed", "a prescribed motion");
  if (j.independent) refuse("independent", "an independent coordinate");
  if (j.parent_node >= 0 || j.parent_node == kTipNode || !j.parent_node_set.empty())
    refuse(j.parent_node_set.empty() ? "parent_node" : "parent_node_set", "a node of a flexible parent");
  if (info.speeds != info.coordinates && !m.loops.empty())
    throw ModelError(m.source_file, j.where + "/type",
                     type + " joint '" + j.name + "' in a model with closed loops",
                     "closed loops are assembled over joints whose coordinates are their speeds' integrals; "
                     "build the motion from revolute and prismatic joints, or open the loop");
}

/// A compound joint's unit axis (a free joint's frame is the joint frame's x, y, z).
Axis checked_axis(const Model& m, const Joint& j) {
  const std::string type = joint_type_info(j.type).name;
  if (j.type == JointType::free) return {0.0, 0.0, 1.0};
  const double norm = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
  if (!std::isfinite(norm) || norm == 0)
    throw ModelError(m.source_file, j.where + "/axis",
                     "axis of " + type + " joint '" + j.name + "' has no direction",
                     "give the normal of the plane, e.g. [0, 0, 1] (it is normalised at load)");
  return {j.axis[0] / norm, j.axis[1] / norm, j.axis[2] / norm};
}

/// No joint or body may already have a name the steps take.
void check_free_names(const Model& m, const Joint& j) {
  std::set<std::string> taken{m.ground};
  for (const Joint& other : m.joints) taken.insert(other.name);
  for (const Body& b : m.bodies) taken.insert(b.name);
  const JointTypeInfo& info = joint_type_info(j.type);
  for (int s = 0; s < info.step_count; ++s) {
    std::vector<std::string> made{step_name(j, info.steps[s])};
    if (s + 1 < info.step_count) made.push_back(frame_name(j, info.steps[s]));
    for (const std::string& name : made)
      if (name != j.name && taken.count(name))
        throw ModelError(m.source_file, j.where + "/name",
                         std::string(info.name) + " joint '" + j.name + "' names its coordinates' joints " +
                             step_names(j, "and") + " and the frames between them <joint>_x_frame, ...; '" +
                             name + "' is already taken",
                         "rename the joint or the body named '" + name + "'");
  }
}

/// Outputs and joint forces name a step, not the compound joint.
void check_references(const Model& m, const Joint& j) {
  const auto refuse = [&](const std::string& place, const std::string& what) {
    throw ModelError(m.source_file, place + "/joint",
                     what + " names " + joint_type_info(j.type).name + " joint '" + j.name + "', which has " +
                         std::to_string(joint_type_info(j.type).coordinates) + " coordinates",
                     "name one of them: " + step_names(j, "or"));
  };
  for (const Output& o : m.outputs)
    if (o.joint == j.name) refuse(o.where, "output '" + o.name + "'");
  for (const JointEffort& e : m.joint_efforts)
    if (e.joint == j.name) refuse(e.where, "joint force '" + e.name + "'");
}

Body massless_frame(const std::string& name, const std::string& where) {
  Body b;
  b.name = name;
  b.mass = Scalar::number(0.0, where);
  for (Scalar& c : b.com) c = Scalar::number(0.0, where);
  for (Scalar& c : b.inertia) c = Scalar::number(0.0, where);
  b.where = where;
  return b;
}

/// `count` values of a joint's initial `values` from `first` on, or none for the defaults.
std::vector<double> slice(const std::vector<double>& values, int first, int count) {
  if (values.empty()) return {};
  return {values.begin() + first, values.begin() + first + count};
}

/// The steps of compound joint j, the frames between them appended to `frames`.
std::vector<Joint> steps_of(const Model& m, const Joint& j, std::vector<Body>& frames) {
  const JointTypeInfo& info = joint_type_info(j.type);
  const std::array<Axis, 3> frame = compound_joint_frame(checked_axis(m, j));
  std::vector<Joint> steps;
  int q_first = 0, u_first = 0;  // the step's first initial coordinate and speed
  for (int s = 0; s < info.step_count; ++s) {
    const JointStep& step = info.steps[s];
    const JointTypeInfo& step_info = joint_type_info(step.type);
    Joint out = j;
    out.name = step_name(j, step);
    out.type = step.type;
    out.axis = frame[static_cast<std::size_t>(step.axis)];
    out.step_q0 = slice(j.step_q0, q_first, step_info.coordinates);
    out.step_u0 = slice(j.step_u0, u_first, step_info.speeds);
    if (step_info.coordinates == 1) {
      out.q0 = out.step_q0.empty() ? 0.0 : out.step_q0[0];
      out.u0 = out.step_u0.empty() ? 0.0 : out.step_u0[0];
      out.step_q0.clear();
      out.step_u0.clear();
    }
    q_first += step_info.coordinates;
    u_first += step_info.speeds;
    if (s > 0) {
      out.parent = frame_name(j, info.steps[s - 1]);
      for (Scalar& c : out.origin_xyz) c = Scalar::number(0.0, j.where);
      for (Scalar& c : out.origin_rpy) c = Scalar::number(0.0, j.where);
    }
    if (s + 1 < info.step_count) {
      out.child = frame_name(j, step);
      frames.push_back(massless_frame(out.child, j.where));
    }
    steps.push_back(std::move(out));
  }
  return steps;
}

}  // namespace

std::array<Axis, 3> compound_joint_frame(const Axis& n) {
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[static_cast<std::size_t>(k)]) < std::abs(n[static_cast<std::size_t>(least)])) least = k;
  Axis e1{0, 0, 0};
  e1[static_cast<std::size_t>(least)] = 1;
  const double along = n[static_cast<std::size_t>(least)];
  for (int k = 0; k < 3; ++k) e1[static_cast<std::size_t>(k)] -= along * n[static_cast<std::size_t>(k)];
  const double norm = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double& c : e1) c /= norm;
  return {e1, cross(n, e1), n};
}

void expand_compound_joints(Model& model) {
  std::vector<Joint> joints;
  std::vector<Body> frames;
  for (const Joint& j : model.joints) {
    if (joint_type_info(j.type).coordinates > 1) check_several_coordinates(model, j);
    if (!joint_type_info(j.type).compound()) {
      joints.push_back(j);
      continue;
    }
    check_free_names(model, j);
    check_references(model, j);
    for (Joint& step : steps_of(model, j, frames)) joints.push_back(std::move(step));
  }
  model.joints = std::move(joints);
  for (Body& b : frames) model.bodies.push_back(std::move(b));
}

}  // namespace kanegen::model
