// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/beam_body.hpp"

#include <memory>
#include <stdexcept>

namespace kanegen::fem {

Eigen::Matrix3d beam_frame(const Eigen::Vector3d& axis, const Eigen::Vector3d& up) {
  if (!(axis.norm() > 0.0)) throw std::invalid_argument("beam_frame: zero axis");
  const Eigen::Vector3d x = axis.normalized();
  const Eigen::Vector3d y_raw = up.cross(x);
  if (y_raw.norm() < 1e-9 * up.norm())
    throw std::invalid_argument("beam_frame: `up` is parallel to the beam");
  const Eigen::Vector3d y = y_raw.normalized();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = x.cross(y);
  return R;
}

int add_beam_run(Body& body, int from, const Eigen::Vector3d& to, int elements, const BeamProperties& beam,
                 const Eigen::Vector3d& up) {
  if (elements < 1) throw std::invalid_argument("add_beam_run: need at least one element");
  const Eigen::Vector3d start = body.node_position(from);
  const Eigen::Vector3d step = (to - start) / elements;
  const Eigen::Matrix3d R = beam_frame(step, up);
  // One element object serves the whole run: the elements are identical.
  const auto element = std::make_shared<const BeamElement>(beam.kind, step.norm(), beam.section,
                                                           beam.material, beam.bending_rotary_inertia);
  int previous = from;
  for (int i = 1; i <= elements; ++i) {
    const int next = body.add_node(i == elements ? to : Eigen::Vector3d(start + i * step));
    body.add_element(element, {previous, next}, R, body.node_position(previous));
    previous = next;
  }
  return previous;
}

Body make_beam_chain(const BeamProperties& beam, double length, int elements, double start) {
  Body body(beam.kind == BeamKind::kPlanar ? planar_layout() : spatial_layout());
  const int first = body.add_node(Eigen::Vector3d(start, 0.0, 0.0));
  add_beam_run(body, first, Eigen::Vector3d(start + length, 0.0, 0.0), elements, beam);
  return body;
}

}  // namespace kanegen::fem
