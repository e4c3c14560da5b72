// SPDX-License-Identifier: GPL-2.0-or-later
// The joint types a model file may name, in one table: what the loaders
// accept (JSON "type", URDF type="..."), how many coordinates each has and
// where it may sit. The checks' messages list the names from here, so a new
// type is named everywhere once it has its row. How a type moves its child
// is said twice on purpose: by the symbolic joint model
// (kinematics/joint_model.*) and by the numeric path's own table
// (numeric/instance.cpp), so that `kanegen verify` compares two derivations.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace kanegen::model {

enum class JointType { revolute, continuous, prismatic, fixed };

struct JointTypeInfo {
  JointType type;
  const char* name;  ///< as a model file spells it (JSON and URDF alike)
  int coordinates;   ///< coordinates, and as many speeds (q_dot = u)
  /// May sit on a node of a flexible parent (a slide there is not derived).
  bool on_nodes;
};

inline constexpr std::array<JointTypeInfo, 4> joint_types{{
    {JointType::revolute, "revolute", 1, true},
    {JointType::continuous, "continuous", 1, true},
    {JointType::prismatic, "prismatic", 1, false},
    {JointType::fixed, "fixed", 0, true},
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

/// The names of the types with coordinates (moving) or without, or of all.
enum class JointKinds { all, moving, on_nodes };
inline std::vector<std::string> joint_type_names(JointKinds kinds = JointKinds::all) {
  std::vector<std::string> names;
  for (const JointTypeInfo& info : joint_types)
    if (kinds == JointKinds::all || (kinds == JointKinds::moving && info.coordinates > 0) ||
        (kinds == JointKinds::on_nodes && info.on_nodes))
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
