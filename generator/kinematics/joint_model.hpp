// SPDX-License-Identifier: GPL-2.0-or-later
// The symbolic joint model, in the spirit of RBDL's jcalc and Pinocchio's
// joint models: what the symbolic stages (kinematics/, kane/) ask of a joint
// type, answered in one place instead of by a switch at each use. A joint of
// one speed has one column of the motion subspace S, in child axes: a turn
// about its axis (angular part) or a slide along it (linear part). Spatial
// pairs are (angular, linear) and wrenches (moment, force), as in
// Featherstone's recursions.
#pragma once

#include <utility>

#include "model/joint_types.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kinematics {

using symbolic::Mat3;
using symbolic::Vec3;

/// The part of a spatial motion that a joint's columns of S lie in.
enum class Column { none, angular, linear };

class JointModel {
 public:
  explicit JointModel(model::JointType type = model::JointType::fixed);

  /// Speeds: 0 (fixed), 1 (q_dot = u), or 3 for a spherical joint (u the
  /// child's angular velocity relative to the joint frame, child axes).
  int speeds() const { return speeds_; }
  bool spherical() const { return speeds_ == 3; }
  /// Column c of S (c < speeds()) lies along axis (one speed) or along
  /// child axis c (spherical).
  Vec3 column_axis(const Vec3& axis, int c) const;
  Column column() const { return column_; }
  bool turns() const { return column_ == Column::angular; }
  bool slides() const { return column_ == Column::linear; }

  /// Of a pair (angular, linear), the part S's column lies in (the angular
  /// one for a joint without a column, which callers then leave alone).
  template <class T>
  T& part(T& angular, T& linear) const {
    return slides() ? linear : angular;
  }
  template <class T>
  const T& part(const T& angular, const T& linear) const {
    return slides() ? linear : angular;
  }

  /// S^T w: the joint's generalized force from a wrench (moment, force) in
  /// child axes: the moment about a turn's axis, the force along a slide's.
  GiNaC::ex force_of(const Vec3& axis, const Vec3& moment, const Vec3& force) const;

  /// The joint's motion in the joint frame for coordinate q: the rotation
  /// (child axes -> joint axes) and the translation of the child origin.
  Mat3 rotation(const Vec3& axis, const GiNaC::ex& q) const;
  Vec3 translation(const Vec3& axis, const GiNaC::ex& q) const;
  /// A spherical joint's rotation (child axes -> joint axes) by the
  /// quaternion w + x i + y j + z k, with s = 2 / (w^2 + x^2 + y^2 + z^2):
  /// divided by its squared length, it stays a rotation when integration
  /// lets the length drift.
  static Mat3 quaternion_rotation(const GiNaC::ex& x, const GiNaC::ex& y, const GiNaC::ex& z,
                                  const GiNaC::ex& w, const GiNaC::ex& s);

  /// S u split: the child's angular and linear velocity relative to the
  /// joint frame, child axes (zero for a part the column is not in).
  Vec3 angular_velocity(const Vec3& axis, const GiNaC::ex& u) const;
  Vec3 linear_velocity(const Vec3& axis, const GiNaC::ex& u) const;

  /// U = I S for a spatial inertia [[A, B], [B^T, C]] (about the child
  /// origin, child axes): (A a, B^T a) for a turn, (B a, C a) for a slide.
  std::pair<Vec3, Vec3> inertia_column(const Mat3& a, const Mat3& b, const Mat3& c, const Vec3& axis) const;

  /// The momentum (angular about the origin, linear) of a composite body
  /// (mass m, first moment h, inertia K about the origin) moving with u = 1
  /// along S alone: (K a, a x h) for a turn, (h x a, m a) for a slide.
  std::pair<Vec3, Vec3> unit_momentum(const GiNaC::ex& mass, const Vec3& moment, const Mat3& second,
                                      const Vec3& axis) const;

 private:
  Column column_ = Column::none;
  int speeds_ = 0;
};

}  // namespace kanegen::kinematics
