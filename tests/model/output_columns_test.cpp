// SPDX-License-Identifier: GPL-2.0-or-later
// The columns the outputs expand into (model/output_columns.hpp), which the
// generated kernels, the numeric derivation and verify all follow.
#include "model/output_columns.hpp"

#include <catch2/catch.hpp>

#include "test_support.hpp"

using namespace kanegen::model;
using kanegen::model::test::source_path;

namespace {

Output output(const std::string& name, OutputKind kind, const std::string& body = "",
              const std::string& loop = "") {
  Output o;
  o.name = name;
  o.kind = kind;
  o.body = body;
  o.loop = loop;
  return o;
}

Loop loop(const std::string& name, LoopType type, bool planar, std::array<double, 3> axis = {0.0, 0.0, 1.0}) {
  Loop l;
  l.name = name;
  l.type = type;
  l.planar = planar;
  l.axis = axis;
  return l;
}

std::vector<std::string> names(const std::vector<OutputColumn>& columns) {
  std::vector<std::string> out;
  for (const OutputColumn& c : columns) out.push_back(c.name);
  return out;
}

}  // namespace

TEST_CASE("each output kind expands into its named columns", "[output_columns]") {
  Model m;
  Body planar, spatial;
  planar.name = "strip";
  planar.flexible = true;
  spatial.name = "shaft";
  spatial.flexible = true;
  spatial.elastic.formulation = BeamFormulation::spatial;
  m.bodies = {planar, spatial};
  m.loops = {loop("hinge", LoopType::revolute, true)};
  m.outputs = {output("tip", OutputKind::point_position, "strip"),
               output("angle", OutputKind::joint_coordinate),
               output("rate", OutputKind::joint_speed),
               output("deflection", OutputKind::node_displacement, "strip"),
               output("N", OutputKind::axial_force, "strip"),
               output("M_strip", OutputKind::bending_moment, "strip"),
               output("M_shaft", OutputKind::bending_moment, "shaft"),
               output("stress", OutputKind::bending_stress, "shaft"),
               output("force", OutputKind::reaction, "", "hinge")};
  const std::vector<OutputColumn> columns = output_columns(m);
  CHECK(names(columns) == std::vector<std::string>{"tip.x", "tip.y", "tip.z", "angle", "rate", "deflection.x",
                                                   "deflection.y", "deflection.z", "N", "M_strip",
                                                   "M_shaft.y", "M_shaft.z", "stress", "force.x", "force.y"});
  const std::vector<int> output = {0, 0, 0, 1, 2, 3, 3, 3, 4, 5, 6, 6, 7, 8, 8};
  // x, y, z = 0, 1, 2; a bending moment about y or z (a planar beam's about z alone); a loop's rows in order.
  const std::vector<int> component = {0, 1, 2, 0, 0, 0, 1, 2, 0, 2, 1, 2, 0, 0, 1};
  REQUIRE(columns.size() == output.size());
  for (std::size_t k = 0; k < columns.size(); ++k) {
    INFO(columns[k].name);
    CHECK(columns[k].output == output[k]);
    CHECK(columns[k].component == component[k]);
    CHECK(columns[k].kind == m.outputs[output[k]].kind);
  }
}

TEST_CASE("a loop's rows are named as the model format lists them", "[output_columns]") {
  using Rows = std::vector<std::string>;
  CHECK(loop_rows(loop("a", LoopType::spherical, false)) == Rows{"x", "y", "z"});
  CHECK(loop_rows(loop("a", LoopType::revolute, true)) == Rows{"x", "y"});
  CHECK(loop_rows(loop("a", LoopType::revolute, true, {1.0, 0.0, 0.0})) == Rows{"f1", "f2"});
  CHECK(loop_rows(loop("a", LoopType::revolute, false)) == Rows{"x", "y", "z", "m1", "m2"});
  CHECK(loop_rows(loop("a", LoopType::slider, true)) == Rows{"n"});
  CHECK(loop_rows(loop("a", LoopType::slider, false)) == Rows{"f1", "f2"});
}

TEST_CASE("outputs naming no loop or body are an error", "[output_columns]") {
  Model m;
  m.outputs = {output("force", OutputKind::reaction, "", "nowhere")};
  CHECK_THROWS_AS(output_columns(m), std::invalid_argument);
  m.outputs = {output("moment", OutputKind::bending_moment, "nobody")};
  CHECK_THROWS_AS(output_columns(m), std::invalid_argument);
}

TEST_CASE("the columns of shipped models", "[output_columns]") {
  CHECK(names(output_columns(load_model(source_path("models/spatial_arm2.json")))) ==
        std::vector<std::string>{"tip1.x", "tip1.y", "tip1.z", "tip2.x", "tip2.y", "tip2.z", "payload.x",
                                 "payload.y", "payload.z", "root_moment.y", "root_moment.z"});
  const Model rsur = load_model(source_path("tests/data/models/rsur_revolute_flexible.json"));
  CHECK(names(output_columns(rsur)) ==
        std::vector<std::string>{"crank", "H_reaction.x", "H_reaction.y", "H_reaction.z", "H_reaction.m1",
                                 "H_reaction.m2", "rocker_tip.x", "rocker_tip.y", "rocker_tip.z"});
}
