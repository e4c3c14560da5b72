// SPDX-License-Identifier: GPL-2.0-or-later
// A node of a flexible body (a beam's node, or a mesh body's interface: its
// averaged node set) as a moving point of its link: where it is and its
// partial velocities for the body's elastic speeds, with the beam's
// foreshortening when it has one (fem/foreshortening.hpp). Node forces, loop
// joints on nodes and node outputs all take the node from here.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <vector>

#include "fem/elastic_model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/vec3.hpp"

namespace kanegen::kane {

struct NodePoint {
  /// The node's displacement T eta + f(eta), link frame.
  symbolic::Vec3 displacement;
  /// The displaced node r + T eta + f(eta), link frame.
  symbolic::Vec3 position;
  /// Per elastic speed k: T_k + D_k(eta), D_k,a = -(H_a eta)_k.
  std::vector<symbolic::Vec3> partial;
  /// The node's small rotation theta = C eta (link axes); kinematics::node_turn makes it exact.
  std::array<GiNaC::ex, 3> rotation;
};

/// `program`: where to name the intermediates; null writes them out in place
/// (for expressions that are differentiated, as the loop equations are).
NodePoint node_point(const fem::ElasticModel& beam, int node, const std::vector<GiNaC::ex>& eta,
                     symbolic::Program* program);

}  // namespace kanegen::kane
