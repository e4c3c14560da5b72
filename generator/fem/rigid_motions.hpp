// SPDX-License-Identifier: GPL-2.0-or-later
// Whether held dofs stop every rigid motion of a body, decided from its
// geometry, not from K: each connected part of the body (elements sharing
// nodes) moves rigidly by u = t + theta x (x - c) at its nodes (with the
// rotation theta at nodes that have rotation dofs), and the held dofs stop
// that part when no such motion vanishes on all of them. The test compares
// orthonormal bases, so it depends neither on the units nor on how thin or
// slender the body is. K's pivots cannot: clamped, a 10 m x 77.5 x 5.16 mm
// C3D20 bar has its smallest pivot 5.1e-7 of the root of K's largest
// diagonal; held so that it can slide, 6.8e-8.
#pragma once

#include <string>

#include "fem/body.hpp"
#include "fem/boundary.hpp"

namespace kanegen::fem {

/// "" if `held` stops every rigid motion of every connected part of `body`;
/// else the first free motion, described: "a translation along (0, 0, 1) of
/// the part with node 0" or "a rotation about the axis (0, 1, 0) through
/// (0, 0, -0.0026) of the part with node 0" (link frame, body node indices).
/// Motions the layout cannot show (out of plane, for a plane body) are not
/// motions. Parts joined at a single node or along an edge count as one
/// part: their relative hinge motion is not seen here.
std::string unheld_rigid_motion(const Body& body, const Constraint& held);

}  // namespace kanegen::fem
