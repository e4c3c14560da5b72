// SPDX-License-Identifier: GPL-2.0-or-later
// The shipped JSON models load with the fields their files give.
#include <catch2/catch.hpp>

#include "test_support.hpp"

using namespace kanegen::model;
using kanegen::model::test::source_path;

namespace {

void check_literal(const Scalar& s, double value) {
  CHECK(s.is_literal);
  CHECK(s.value == Approx(value));
}
void check_expression(const Scalar& s, const std::string& text) {
  CHECK_FALSE(s.is_literal);
  CHECK(s.text == text);
}

}  // namespace

TEST_CASE("simple_pendulum.json loads", "[json]") {
  const std::string file = source_path("models/simple_pendulum.json");
  const Model m = load_model(file);
  CHECK(m.name == "simple_pendulum");
  CHECK(m.source_file == file);
  CHECK(m.ground == "ground");
  REQUIRE(m.parameters.size() == 3);
  CHECK(m.parameters[0].name == "m");  // file order, not alphabetical
  CHECK(m.parameters[1].name == "l");
  CHECK(m.parameters[2].name == "g");
  CHECK(m.parameters[2].value == Approx(9.81));
  CHECK(m.parameters[2].where == "/parameters/g");
  check_literal(m.gravity[0], 0);
  check_expression(m.gravity[2], "-g");
  CHECK(m.gravity[2].where == "/gravity/2");

  REQUIRE(m.bodies.size() == 1);
  const Body& b = m.bodies[0];
  CHECK(b.name == "pendulum");
  CHECK(b.where == "/bodies/0");
  check_expression(b.mass, "m");
  CHECK(b.mass.where == "/bodies/0/mass");
  check_literal(b.com[0], 0);
  check_expression(b.com[2], "-l");
  for (const Scalar& s : b.inertia) check_literal(s, 0);  // a point mass
  CHECK(b.inertia[3].where == "/bodies/0/inertia/ixy");

  REQUIRE(m.joints.size() == 1);
  const Joint& j = m.joints[0];
  CHECK(j.name == "pivot");
  CHECK(j.type == JointType::revolute);
  CHECK(j.parent == "ground");
  CHECK(j.child == "pendulum");
  CHECK(j.axis == std::array<double, 3>{0, 1, 0});
  for (int k = 0; k < 3; ++k) {
    check_literal(j.origin_xyz[k], 0);
    check_literal(j.origin_rpy[k], 0);
  }
  check_literal(j.spring_stiffness, 0);
  check_literal(j.damping, 0);
  CHECK(j.actuated);
  CHECK(j.q0 == Approx(0.5));
  CHECK(j.u0 == 0);

  CHECK(m.forces.empty());
  REQUIRE(m.outputs.size() == 2);
  CHECK(m.outputs[0].name == "bob");
  CHECK(m.outputs[0].kind == OutputKind::point_position);
  CHECK(m.outputs[0].body == "pendulum");
  check_expression(m.outputs[0].point[2], "-l");
  CHECK(m.outputs[1].name == "angle");
  CHECK(m.outputs[1].kind == OutputKind::joint_coordinate);
  CHECK(m.outputs[1].joint == "pivot");
}

TEST_CASE("double_pendulum.json loads", "[json]") {
  const Model m = load_model(source_path("models/double_pendulum.json"));
  CHECK(m.name == "double_pendulum");
  REQUIRE(m.parameters.size() == 6);
  CHECK(m.parameters[4].name == "c1");
  CHECK(m.parameters[4].value == 0);
  check_literal(m.gravity[2], -9.81);

  REQUIRE(m.bodies.size() == 2);
  check_expression(m.bodies[0].mass, "m1");
  check_expression(m.bodies[0].com[0], "l1/2");
  check_literal(m.bodies[0].inertia[0], 0);
  check_expression(m.bodies[0].inertia[1], "m1*l1^2/12");
  check_expression(m.bodies[1].inertia[2], "m2*l2^2/12");
  check_literal(m.bodies[1].inertia[5], 0);

  REQUIRE(m.joints.size() == 2);
  CHECK(m.joints[0].name == "shoulder");
  CHECK(m.joints[1].name == "elbow");
  CHECK(m.joints[1].parent == "link1");
  check_expression(m.joints[1].origin_xyz[0], "l1");
  CHECK(m.joints[1].origin_xyz[0].where == "/joints/1/origin/xyz/0");
  check_expression(m.joints[0].damping, "c1");
  check_expression(m.joints[1].damping, "c2");

  REQUIRE(m.outputs.size() == 3);
  CHECK(m.outputs[0].name == "tip");
  CHECK(m.outputs[0].body == "link2");
  check_expression(m.outputs[0].point[0], "l2");
}
