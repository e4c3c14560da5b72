// SPDX-License-Identifier: GPL-2.0-or-later
// The joint types a model file may name, in one table: what the loaders
// accept (JSON "type", URDF type="..."), how many coordinates each has and
// where it may sit. The checks' messages list the names from here, so a new
// type is named everywhere once it has its row. How a type moves its child
// is said twice on purpose: by the symbolic joint model
// (kinematics/joint_model.*) and by the numeric path's own table
// (numeric/instance.cpp), so that `kanegen verify` compares two derivations.
// A compound type (planar, free) is a row of steps: the loaders replace it by
// one joint of a primitive type per step (model/joint_expansion.hpp), so no
// later stage sees it. A spherical joint is primitive but has more
// coordinates than speeds: a unit quaternion and the child's angular
// velocity in its own axes, q_dot = N(q) u (docs/model-format.md).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace kanegen::model {

enum class JointType { revolute, continuous, prismatic, fixed, planar, spherical, free };

/// One step of a compound type: a joint of a primitive type along or about
/// one axis of the compound joint's frame (0, 1: the two unit vectors across
/// its axis, model/joint_expansion.hpp; 2: its axis), whose coordinate is
/// named <joint>_<suffix>; a step with the suffix "" keeps the joint's name.
struct JointStep {
  JointType type;
  int axis;
  const char* suffix;
};

struct JointTypeInfo {
  JointType type;
  const char* name;  ///< as a model file spells it (JSON and URDF alike)
  int coordinates;   ///< coordinates (q)
  int speeds;        ///< speeds (u): as many as coordinates (q_dot = u) but for a quaternion's
  /// May sit on a node of a flexible parent (a slide there is not derived).
  bool on_nodes;
  /// SI units of one coordinate, one speed and one generalized force of the
  /// type, as an FMU declares them ("rad", "rad/s", "N.m" for a turn; "m",
  /// "m/s", "N" for a slide; "" where there is no one unit: a quaternion's
  /// components, and what a compound type's steps have instead).
  const char* coordinate_unit;
  const char* speed_unit;
  const char* force_unit;
  /// A compound type's steps (step_count of them), in the order of its
  /// coordinates; a primitive type has none.
  int step_count = 0;
  std::array<JointStep, 4> steps{};

  bool compound() const { return step_count > 0; }
};

inline constexpr std::array<JointTypeInfo, 7> joint_types{{
    {JointType::revolute, "revolute", 1, 1, true, "rad", "rad/s", "N.m"},
    {JointType::continuous, "continuous", 1, 1, true, "rad", "rad/s", "N.m"},
    {JointType::prismatic, "prismatic", 1, 1, false, "m", "m/s", "N"},
    {JointType::fixed, "fixed", 0, 0, true, "", "", ""},
    // URDF's planar: the child slides in the plane across the axis and turns about it.
    {JointType::planar,
     "planar",
     3,
     3,
     false,
     "",
     "",
     "",
     3,
     {{{JointType::prismatic, 0, "x"}, {JointType::prismatic, 1, "y"}, {JointType::revolute, 2, "theta"}}}},
    // A ball joint (MuJoCo's ball): quaternion (x, y, z, w) and angular velocity in child axes.
    {JointType::spherical, "spherical", 4, 3, false, "", "rad/s", "N.m"},
    // Six degrees of freedom (MuJoCo's free, URDF's floating): slides along the
    // joint frame's x, y, z, then a spherical joint that keeps the joint's name.
    {JointType::free,
     "free",
     7,
     6,
     false,
     "",
     "",
     "",
     4,
     {{{JointType::prismatic, 0, "x"},
       {JointType::prismatic, 1, "y"},
       {JointType::prismatic, 2, "z"},
       {JointType::spherical, 2, ""}}}},
}};

inline const JointTypeInfo& joint_type_info(JointType type) {
  for (const JointTypeInfo& info : joint_types)
    if (info.type == type) return info;
  throw std::logic_error("joint type without a row in model/joint_types.hpp");
}

/// The row of a type name, or nullptr if no type is so named.
inline const JointTypeInfo* joint_type_named(const std::string& name) {
  for (const JointTypeInfo& info : joint_types)
    if (name == info.name) return &info;
  return nullptr;
}

/// The names of all types, of those with coordinates (moving), of those
/// that may sit on a node, or of those of one coordinate (what an output, a
/// joint force or a loop's independent coordinate names: a compound joint's
/// steps are named instead of it).
enum class JointKinds { all, moving, on_nodes, one_coordinate };
inline std::vector<std::string> joint_type_names(JointKinds kinds = JointKinds::all) {
  std::vector<std::string> names;
  for (const JointTypeInfo& info : joint_types)
    if (kinds == JointKinds::all || (kinds == JointKinds::moving && info.coordinates > 0) ||
        (kinds == JointKinds::on_nodes && info.on_nodes) ||
        (kinds == JointKinds::one_coordinate && info.coordinates == 1))
      names.push_back(info.name);
  return names;
}

/// "a, b or c" (conjunction "or"), "a, b and c" ("and"); separator ", " alone for a list.
inline std::string joint_type_list(JointKinds kinds, const std::string& conjunction) {
  const std::vector<std::string> names = joint_type_names(kinds);
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " " + conjunction + " " : ", ") + names[i];
  return out;
}

}  // namespace kanegen::model
