// SPDX-License-Identifier: GPL-2.0-or-later
// URDF import: joint order from the file, inertia rotated from the inertial
// frame into link axes, the root link as the ground.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "test_support.hpp"

using namespace kanegen::model;
using kanegen::model::test::test_data;

namespace {

/// "line N: <joint name=\"x\">" with N looked up in the file.
std::string place_of(const std::string& file, const std::string& tag) {
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.find("<" + tag) != std::string::npos) return "line " + std::to_string(n) + ": <" + tag + ">";
  return "(not found)";
}

std::array<double, 6> inertia(const Body& b) {
  std::array<double, 6> out{};
  for (int k = 0; k < 6; ++k) {
    CHECK(b.inertia[k].is_literal);
    out[k] = b.inertia[k].value;
  }
  return out;
}

void check_inertia(const Body& b, const std::array<double, 6>& expected) {
  const auto got = inertia(b);
  for (int k = 0; k < 6; ++k) {
    INFO(b.name << " inertia entry " << k);
    CHECK(got[k] == Approx(expected[k]).margin(1e-14));
  }
}

}  // namespace

TEST_CASE("URDF: names, root as ground, joint order", "[urdf]") {
  const std::string file = test_data("arm.urdf");
  const Model m = load_model(file);
  CHECK(m.name == "test_arm_2");  // "test-arm 2" sanitised
  CHECK(m.source_file == file);
  CHECK(m.ground == "world");
  REQUIRE(m.bodies.size() == 4);  // world is the ground, not a body
  CHECK(m.bodies[0].name == "link1");
  CHECK(m.bodies[3].name == "tool");
  REQUIRE(m.joints.size() == 4);
  // File order; urdfdom's std::map would give a_slide, elbow, shoulder, tool_mount.
  CHECK(m.joints[0].name == "shoulder");
  CHECK(m.joints[1].name == "elbow");
  CHECK(m.joints[2].name == "tool_mount");
  CHECK(m.joints[3].name == "a_slide");
  CHECK(m.joints[0].where == place_of(file, "joint name=\"shoulder\""));
  CHECK(m.bodies[1].where == place_of(file, "link name=\"link2\""));
  CHECK(m.joints[0].parent == "world");
  CHECK(m.joints[3].parent == "link2");
  CHECK(m.joints[3].child == "link3");
}

TEST_CASE("URDF: joints", "[urdf]") {
  const Model m = load_model(test_data("arm.urdf"));
  const Joint& shoulder = m.joints[0];
  CHECK(shoulder.type == JointType::revolute);
  CHECK(shoulder.axis == std::array<double, 3>{0, 0, 1});  // "0 0 2" normalised
  CHECK(shoulder.origin_xyz[2].value == Approx(0.5));
  CHECK(shoulder.damping.value == Approx(0.7));  // <dynamics damping>
  CHECK(shoulder.actuated);
  const Joint& elbow = m.joints[1];
  CHECK(elbow.type == JointType::continuous);
  CHECK(elbow.axis == std::array<double, 3>{1, 0, 0});  // URDF default axis
  CHECK(elbow.origin_rpy[0].value == Approx(std::acos(-1.0) / 2));
  CHECK(elbow.origin_rpy[1].value == Approx(0).margin(1e-12));
  CHECK(elbow.origin_rpy[2].value == Approx(0).margin(1e-12));
  CHECK(elbow.damping.value == 0);
  CHECK(m.joints[2].type == JointType::fixed);
  CHECK(m.joints[3].type == JointType::prismatic);
  for (const Joint& j : m.joints) {
    CHECK(j.spring_stiffness.value == 0);
    CHECK(j.q0 == 0);
    CHECK(j.u0 == 0);
  }
}

TEST_CASE("URDF: inertia rotated from the inertial frame into link axes", "[urdf]") {
  const Model m = load_model(test_data("arm.urdf"));
  const Body& link1 = m.bodies[0];
  CHECK(link1.mass.value == 2);
  CHECK(link1.com[2].value == Approx(0.2));
  check_inertia(link1, {0.02, 0.03, 0.04, 0.001, 0, 0});  // unrotated: as written

  // link2: diag(1, 2, 3) in a frame turned by 0.5 rad about z. With R = Rz(a),
  // R D R^T = [c^2 + 2 s^2, -c s, 0; -c s, s^2 + 2 c^2, 0; 0, 0, 3].
  const double c = std::cos(0.5), s = std::sin(0.5);
  const Body& link2 = m.bodies[1];
  CHECK(link2.mass.value == 1.5);
  CHECK(link2.com[0].value == Approx(0.25));
  check_inertia(link2, {c * c + 2 * s * s, s * s + 2 * c * c, 3, -c * s, 0, 0});

  // link3: diag(1, 2, 3) turned by 0.3 rad about x: the y-z block becomes
  // [2 c^2 + 3 s^2, -c s; -c s, 2 s^2 + 3 c^2].
  const double c3 = std::cos(0.3), s3 = std::sin(0.3);
  const Body& link3 = m.bodies[2];
  CHECK(link3.com[1].value == Approx(0.1));
  check_inertia(link3, {1, 2 * c3 * c3 + 3 * s3 * s3, 2 * s3 * s3 + 3 * c3 * c3, 0, 0, -c3 * s3});

  const Body& tool = m.bodies[3];  // no <inertial>: a massless frame
  CHECK(tool.mass.value == 0);
  check_inertia(tool, {0, 0, 0, 0, 0, 0});
}

TEST_CASE("URDF: load options", "[urdf]") {
  const Model standard = load_model(test_data("arm.urdf"));
  CHECK(standard.gravity[0].value == 0);
  CHECK(standard.gravity[2].value == Approx(-9.81));

  LoadOptions options;
  options.urdf_gravity = {0, -9.81, 0};
  options.urdf_joint_damping = false;
  const Model custom = load_model(test_data("arm.urdf"), options);
  CHECK(custom.gravity[1].value == Approx(-9.81));
  CHECK(custom.gravity[2].value == 0);
  CHECK(custom.joints[0].damping.value == 0);
}
