// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/output_columns.hpp"

#include <algorithm>
#include <stdexcept>

namespace kanegen::model {
namespace {

bool planar_beam(const Model& model, const Output& output) {
  const auto body = std::find_if(model.bodies.begin(), model.bodies.end(),
                                 [&](const Body& b) { return b.name == output.body; });
  if (body == model.bodies.end()) throw std::invalid_argument("output '" + output.name + "' names no body");
  return body->elastic.formulation == BeamFormulation::planar;
}

const Loop& loop_of(const Model& model, const Output& output) {
  const auto loop = std::find_if(model.loops.begin(), model.loops.end(),
                                 [&](const Loop& l) { return l.name == output.loop; });
  if (loop == model.loops.end()) throw std::invalid_argument("output '" + output.name + "' names no loop");
  return *loop;
}

}  // namespace

std::vector<std::string> loop_rows(const Loop& loop) {
  const bool z_plane = loop.axis == std::array<double, 3>{0.0, 0.0, 1.0};
  switch (loop.type) {
    case LoopType::spherical:
      return {"x", "y", "z"};
    case LoopType::revolute:
      if (!loop.planar) return {"x", "y", "z", "m1", "m2"};
      return z_plane ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"f1", "f2"};
    case LoopType::slider:
      return loop.planar ? std::vector<std::string>{"n"} : std::vector<std::string>{"f1", "f2"};
  }
  throw std::logic_error("loop_rows: unknown loop type");
}

std::vector<OutputColumn> output_columns(const Model& model) {
  static const char* const axes[] = {"x", "y", "z"};
  std::vector<OutputColumn> columns;
  for (std::size_t k = 0; k < model.outputs.size(); ++k) {
    const Output& o = model.outputs[k];
    const auto add = [&](const std::string& suffix, int component) {
      columns.push_back(
          {suffix.empty() ? o.name : o.name + "." + suffix, o.kind, static_cast<int>(k), component});
    };
    switch (o.kind) {
      case OutputKind::point_position:
      case OutputKind::node_displacement:
        for (int a = 0; a < 3; ++a) add(axes[a], a);
        break;
      case OutputKind::bending_moment:
        if (planar_beam(model, o)) {
          add("", 2);
        } else {
          add("y", 1);
          add("z", 2);
        }
        break;
      case OutputKind::reaction: {
        const std::vector<std::string> rows = loop_rows(loop_of(model, o));
        for (std::size_t r = 0; r < rows.size(); ++r) add(rows[r], static_cast<int>(r));
        break;
      }
      default:  // joint coordinate and speed, axial force, bending stress: one value
        add("", 0);
    }
  }
  return columns;
}

}  // namespace kanegen::model
