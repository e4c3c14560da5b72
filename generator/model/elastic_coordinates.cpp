// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/elastic_coordinates.hpp"

namespace kanegen::model {
namespace {

/// Whether the support holds this dof of `node` (of `last`, the last node)
/// at zero; docs/model-format.md, "Support".
bool held(BeamSupport support, bool planar, int node, int last, const std::string& kind) {
  switch (support) {
    case BeamSupport::clamped:
      return node == 0;
    case BeamSupport::pinned_pinned:
      if (node == 0) return kind == "u" || kind == "v" || (!planar && (kind == "w" || kind == "theta_x"));
      return node == last && (kind == "v" || (!planar && kind == "w"));
    case BeamSupport::free:
      return false;
  }
  return false;
}

}  // namespace

std::vector<std::string> elastic_coordinate_names(const ElasticPart& beam) {
  std::vector<std::string> names;
  const int modes = beam.assumed_modes.empty() ? beam.modes : static_cast<int>(beam.assumed_modes.size());
  if (modes > 0) {
    for (int k = 1; k <= modes; ++k) names.push_back("mode" + std::to_string(k));
    return names;
  }
  const bool planar = beam.formulation == BeamFormulation::planar;
  const std::vector<std::string> kinds =
      planar ? std::vector<std::string>{"u", "v", "theta_z"}
             : std::vector<std::string>{"u", "v", "w", "theta_x", "theta_y", "theta_z"};
  const int last = beam.num_nodes() - 1;
  for (int node = 0; node <= last; ++node)
    for (const std::string& kind : kinds)
      if (!held(beam.support, planar, node, last, kind))
        names.push_back("n" + std::to_string(node) + "." + kind);
  return names;
}

}  // namespace kanegen::model
