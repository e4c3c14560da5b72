// SPDX-License-Identifier: GPL-2.0-or-later
// The generalized inertia and elastic forces of one flexible body in its
// link frame (floating frame of reference), built from the inertia
// invariants of the finite-element layer: constant matrices (numbers in the
// generated code) times the elastic coordinates eta, their rates and the
// link's motion. Nothing is integrated point by point (formulation.md
// section 3). fem/floating_frame.hpp is the numeric statement of the same
// formulas. With geometric stiffening, the beam's foreshortening
// (fem/foreshortening.hpp) enters the positions and partial velocities, which
// gives the geometric stiffness of every load with its reaction on the joints.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "fem/elastic_model.hpp"
#include "kinematics/tree_kinematics.hpp"
#include "symbolic/program.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

using symbolic::Mat3;
using symbolic::Vec3;

struct FlexibleTerms {
  /// The deformed body's mass, first moment int rho p and second moment
  /// int rho (|p|^2 1 - p p^T) + J about the link origin, link axes: its
  /// share of the composite inertia seen by the rigid speeds.
  GiNaC::ex mass;
  Vec3 first_moment;
  Mat3 second_moment;
  /// Minus the resultant force and moment (about the link origin) of
  /// int rho a dV with u_dot = 0, gravity included: to add to the link's wrench.
  Vec3 force, moment;
  /// Per elastic speed k: the linear and angular momentum (about the link
  /// origin, link axes) of the body moving with eta_dot_k = 1 alone.
  std::vector<Vec3> linear_momentum, angular_momentum;
  /// n: the elastic equations' forcing: -int rho (N + D)^T a (u_dot = 0) - K eta - C eta_dot.
  std::vector<GiNaC::ex> elastic_forcing;
  /// n x n, row-major: int rho N^T N + Nrot^T J Nrot; a mesh body with
  /// stiffening adds the terms of u2 (int rho (N + D)^T (N + D) - N^T N).
  std::vector<GiNaC::ex> elastic_mass;
  /// Kinetic energy of the body, and its strain energy 1/2 eta^T K eta.
  GiNaC::ex kinetic_energy, strain_energy;
  /// The power of the structural damping, -eta_dot^T C eta_dot.
  GiNaC::ex damping_power;
};

/// `eta`, `eta_dot`: the body's elastic coordinates and speeds; `b`: its
/// link's kinematics (accel_rest carries gravity). The foreshortening is
/// taken when the beam has one (geometric stiffening).
FlexibleTerms flexible_terms(const fem::ElasticModel& beam, const kinematics::BodyState& b,
                             const std::vector<GiNaC::ex>& eta, const std::vector<GiNaC::ex>& eta_dot,
                             symbolic::Program& program);

/// The matrix with the round-off of exact zeros (entries at most 1e-13 of
/// its largest) set to zero, so that sparsity shows in the generated code.
/// Applied to a row, the threshold is relative to that row.
Eigen::MatrixXd cleaned(const Eigen::MatrixXd& m);

/// sum_k c_k x_k over the nonzero c_k, as one sum.
GiNaC::ex linear_combination(const Eigen::Ref<const Eigen::VectorXd>& c, const std::vector<GiNaC::ex>& x);

}  // namespace kanegen::kane
