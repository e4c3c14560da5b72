// SPDX-License-Identifier: GPL-2.0-or-later
#include "kinematics/joint_model.hpp"

#include <stdexcept>

#include "kinematics/tree_kinematics.hpp"

namespace kanegen::kinematics {

using GiNaC::ex;
using namespace symbolic;

namespace {

/// The joint table of the symbolic side: the column each type's speed moves.
/// (The numeric path keeps its own, numeric/instance.cpp, so that `kanegen
/// verify` does not share it.) No default: a new type is a compile error here.
Column column_of(model::JointType type) {
  switch (type) {
    case model::JointType::revolute:
    case model::JointType::continuous:
    case model::JointType::spherical:
      return Column::angular;
    case model::JointType::prismatic:
      return Column::linear;
    case model::JointType::fixed:
      return Column::none;
    case model::JointType::planar:  // compound: the loaders made it primitive steps
    case model::JointType::free:
      throw std::logic_error(
          "a compound joint type reached the symbolic joint model (model/joint_expansion.hpp)");
  }
  return Column::none;
}

}  // namespace

JointModel::JointModel(model::JointType type)
    : column_(column_of(type)), speeds_(model::joint_type_info(type).speeds) {}

Vec3 JointModel::column_axis(const Vec3& axis, int c) const {
  if (!spherical()) return axis;
  Vec3 unit = zero_vec();
  unit[c] = 1;
  return unit;
}

Mat3 JointModel::quaternion_rotation(const ex& x, const ex& y, const ex& z, const ex& w, const ex& s) {
  return {1 - s * (y * y + z * z), s * (x * y - w * z),     s * (x * z + w * y),
          s * (x * y + w * z),     1 - s * (x * x + z * z), s * (y * z - w * x),
          s * (x * z - w * y),     s * (y * z + w * x),     1 - s * (x * x + y * y)};
}

ex JointModel::force_of(const Vec3& axis, const Vec3& moment, const Vec3& force) const {
  return dot(axis, part(moment, force));
}

Vec3 JointModel::angular_velocity(const Vec3& axis, const ex& u) const {
  return turns() ? u * axis : zero_vec();
}

Vec3 JointModel::linear_velocity(const Vec3& axis, const ex& u) const {
  return slides() ? u * axis : zero_vec();
}

Mat3 JointModel::rotation(const Vec3& axis, const ex& q) const {
  return turns() ? rotation_about(axis, q) : identity_mat();
}

Vec3 JointModel::translation(const Vec3& axis, const ex& q) const { return slides() ? q * axis : zero_vec(); }

std::pair<Vec3, Vec3> JointModel::inertia_column(const Mat3& a, const Mat3& b, const Mat3& c,
                                                 const Vec3& axis) const {
  if (slides()) return {mul(b, axis), mul(c, axis)};
  return {mul(a, axis), mul_transposed(b, axis)};
}

std::pair<Vec3, Vec3> JointModel::unit_momentum(const ex& mass, const Vec3& moment, const Mat3& second,
                                                const Vec3& axis) const {
  if (slides()) return {cross(moment, axis), mass * axis};
  return {mul(second, axis), cross(axis, moment)};
}

}  // namespace kanegen::kinematics
