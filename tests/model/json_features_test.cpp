// SPDX-License-Identifier: GPL-2.0-or-later
// Format features the shipped models do not use: defaults, springs, fixed
// joints, forces, axis normalisation, "$schema".
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/schema.hpp"
#include "test_support.hpp"

using namespace kanegen::model;
using kanegen::model::test::test_data;

TEST_CASE("JSON defaults and optional features", "[json]") {
  const Model m = load_model(test_data("features.json"));
  CHECK(m.gravity[2].is_literal);
  CHECK(m.gravity[2].value == Approx(-9.81));

  const Joint& slide = m.joints[0];
  CHECK(slide.type == JointType::prismatic);
  CHECK(slide.axis[0] == Approx(0.6));  // [3, 0, 4] normalised
  CHECK(slide.axis[1] == 0);
  CHECK(slide.axis[2] == Approx(0.8));
  CHECK_FALSE(slide.spring_stiffness.is_literal);
  CHECK(slide.spring_stiffness.text == "k");
  CHECK(slide.spring_rest.value == Approx(0.1));
  CHECK(slide.damping.value == Approx(0.5));
  CHECK_FALSE(slide.actuated);
  CHECK(slide.q0 == Approx(0.2));
  CHECK(slide.u0 == Approx(-1));

  const Joint& hinge = m.joints[1];
  CHECK(hinge.type == JointType::continuous);
  CHECK(hinge.axis == std::array<double, 3>{0, 0, 1});  // default axis
  CHECK(hinge.origin_rpy[1].text == "pi/2");
  CHECK(hinge.actuated);

  const Joint& mount = m.joints[2];
  CHECK(mount.type == JointType::fixed);
  CHECK_FALSE(mount.moves());
  CHECK_FALSE(mount.actuated);

  CHECK(m.bodies[0].inertia[3].value == Approx(0.01));  // ixy
  CHECK(m.bodies[2].mass.value == 0);                   // a massless frame on a fixed joint is fine

  REQUIRE(m.forces.size() == 2);
  CHECK(m.forces[0].frame == ForceFrame::body);
  CHECK(m.forces[0].force[2].text == "-m*sin(pi/6)");
  CHECK(m.forces[1].frame == ForceFrame::world);
  CHECK(m.forces[1].point[0].value == 0);
  CHECK(m.outputs[0].kind == OutputKind::joint_speed);
  CHECK(m.outputs[0].joint == "slide");
}

TEST_CASE("initial values of elastic coordinates are read by name, the others start at 0",
          "[json][flexible]") {
  const Model m = load_model(test_data("elastic_initial.json"));
  const ElasticPart& rod = m.bodies[0].elastic;  // nodal, pinned-pinned
  CHECK(rod.initial_q == std::map<std::string, double>{{"n1.v", 0.002}, {"n2.u", -1e-5}});
  CHECK(rod.initial_u == std::map<std::string, double>{{"n0.theta_z", 0.25}});
  const ElasticPart& arm = m.bodies[1].elastic;  // modal
  CHECK(arm.initial_q.empty());
  CHECK(arm.initial_u == std::map<std::string, double>{{"mode3", -0.5}});
}

TEST_CASE("the schema is embedded and matches models/schema", "[json]") {
  std::ifstream in(kanegen::model::test::source_path("models/schema/kanegen-model.schema.json"));
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str() == model_schema_text());
}

TEST_CASE("every joint type of the table loads from a JSON model as that type", "[json][joint]") {
  // One model per row of model/joint_types.hpp: a new type is tested here
  // without a line for it.
  for (const JointTypeInfo& row : joint_types) {
    INFO(row.name);
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("kanegen_joint_type_" + std::to_string(::getpid()) + "_" + row.name + ".json"))
                                 .string();
    std::ofstream(path) << R"({"format": "kanegen-model", "version": 1, "name": "one_joint",
      "bodies": [{"name": "a", "mass": 1, "com": [1, 0, 0]}, {"name": "b", "mass": 1, "com": [1, 0, 0]}],
      "joints": [{"name": "first", "type": "revolute", "parent": "ground", "child": "a"},
                 {"name": "second", "type": ")"
                        << row.name << R"(", "parent": "a", "child": "b"}]})";
    const Model m = load_model(path);
    CHECK(joint_type_named(row.name) == &row);
    if (row.compound()) {  // loaded as its steps, which share its coordinates (joint_expansion_test.cpp)
      REQUIRE(m.joints.size() == 1 + static_cast<std::size_t>(row.step_count));
      int coordinates = 0, speeds = 0;
      for (int s = 0; s < row.step_count; ++s) {
        CHECK(m.joints[1 + s].type == row.steps[s].type);
        const std::string suffix = row.steps[s].suffix;
        CHECK(m.joints[1 + s].name == (suffix.empty() ? "second" : "second_" + suffix));
        CHECK_FALSE(joint_type_info(row.steps[s].type).compound());
        coordinates += joint_type_info(row.steps[s].type).coordinates;
        speeds += joint_type_info(row.steps[s].type).speeds;
      }
      CHECK(coordinates == row.coordinates);
      CHECK(speeds == row.speeds);
      std::filesystem::remove(path);
      continue;
    }
    REQUIRE(m.joints.size() == 2);
    CHECK(m.joints[1].type == row.type);
    CHECK(m.joints[1].moves() == (row.coordinates > 0));
    std::filesystem::remove(path);
  }
  CHECK(joint_type_named("hinge") == nullptr);
}

TEST_CASE("springs and joint efforts are read by type, constant forces by default",
          "[json][spring][effort]") {
  const Model m = load_model(kanegen::model::test::source_path("tests/data/models/force_elements.json"));
  REQUIRE(m.springs.size() == 2);
  const Spring& anchor = m.springs[0];
  CHECK(anchor.name == "anchor");
  CHECK(anchor.where == "/forces/0");
  CHECK(anchor.body == "lower");
  CHECK(anchor.point[2].text == "-l2");
  CHECK(anchor.body2 == "ground");
  CHECK(anchor.point2[1].value == Approx(0.2));
  CHECK(anchor.stiffness.text == "k1");
  CHECK(anchor.rest_length.text == "l01");
  CHECK(anchor.damping.text == "c1");
  CHECK(m.springs[1].body2 == "upper");

  REQUIRE(m.joint_efforts.size() == 2);
  CHECK(m.joint_efforts[0].joint == "shoulder");
  CHECK(m.joint_efforts[0].value.text == "A*sin(w*t)");  // t is allowed in an effort
  CHECK(m.joint_efforts[0].where == "/forces/2");
  CHECK(m.joint_efforts[1].value.text == "F");

  REQUIRE(m.forces.size() == 1);  // no "type": a constant force
  CHECK(m.forces[0].name == "wind");
  CHECK(m.forces[0].where == "/forces/4");

  // Default: no damping.
  const Model pendulum =
      load_model(kanegen::model::test::source_path("tests/data/models/spring_pendulum.json"));
  CHECK(pendulum.springs[0].rest_length.text == "l01");
  CHECK(pendulum.springs[0].damping.is_literal);
  CHECK(pendulum.springs[0].damping.value == 0);
}
