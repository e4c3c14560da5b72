// SPDX-License-Identifier: GPL-2.0-or-later
// Building bodies out of beams: straight runs of equal elements between
// nodes, a chain along the link x axis, and the element frame of a beam.
#pragma once

#include <Eigen/Dense>

#include "fem/beam_element.hpp"
#include "fem/body.hpp"

namespace kanegen::fem {

struct BeamProperties {
  BeamKind kind = BeamKind::kPlanar;
  BeamSection section;
  Material material;
  bool bending_rotary_inertia = false;
};

/// R^e for a beam along `axis` (link frame): x_e = axis / |axis|,
/// y_e = up x x_e / |.|, z_e = x_e x y_e, so z_e lies in the plane of x_e and
/// `up` (default link z; a planar body needs up = z). Throws if up || axis.
Eigen::Matrix3d beam_frame(const Eigen::Vector3d& axis, const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

/// Adds `elements` equal beams from node `from` to a new node at `to` (link
/// frame), creating elements - 1 inner nodes; returns the last node's index.
int add_beam_run(Body& body, int from, const Eigen::Vector3d& to, int elements, const BeamProperties& beam,
                 const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

/// A straight beam on the link x axis from x = start to x = start + length,
/// nodes 0 .. elements in order of x (node 0 at the joint).
Body make_beam_chain(const BeamProperties& beam, double length, int elements, double start = 0.0);

}  // namespace kanegen::fem
