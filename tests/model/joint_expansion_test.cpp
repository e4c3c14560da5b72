// SPDX-License-Identifier: GPL-2.0-or-later
// Compound joints (planar) are loaded as their steps: names, types, axes,
// frames and initial values, from JSON and URDF alike, and the errors of
// what a compound joint cannot carry or be named as.
#include "model/joint_expansion.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "test_support.hpp"

using namespace kanegen::model;
using kanegen::model::test::expect_model_error;
using kanegen::model::test::source_path;

namespace {

/// A model file with `text`, removed when the test ends.
struct TempModel {
  std::string path;
  TempModel(const std::string& stem, const std::string& extension, const std::string& text)
      : path((std::filesystem::temp_directory_path() /
              ("kanegen_expansion_" + std::to_string(::getpid()) + "_" + stem + extension))
                 .string()) {
    std::ofstream(path) << text;
  }
  ~TempModel() { std::filesystem::remove(path); }
};

/// A JSON model with a planar joint "p" from the ground to body "b"; `joint`
/// adds keys to the joint, `rest` top-level keys.
std::string planar_json(const std::string& joint, const std::string& rest = "") {
  return R"({"format": "kanegen-model", "version": 1, "name": "planar_case",
    "bodies": [{"name": "b", "mass": 1, "inertia": {"ixx": 1, "iyy": 1, "izz": 1}}],
    "joints": [{"name": "p", "type": "planar", "parent": "ground", "child": "b")" +
         joint + "}]" + rest + "}";
}

const Joint& joint_named(const Model& m, const std::string& name) {
  for (const Joint& j : m.joints)
    if (j.name == name) return j;
  FAIL("no joint " << name);
  throw;
}

}  // namespace

TEST_CASE("the plane's axes across a planar joint's normal", "[model][planar]") {
  using A = std::array<double, 3>;
  const auto frame_z = compound_joint_frame({0, 0, 1});
  CHECK(frame_z[0] == A{1, 0, 0});
  CHECK(frame_z[1] == A{0, 1, 0});
  const auto frame_x = compound_joint_frame({1, 0, 0});
  CHECK(frame_x[0] == A{0, 1, 0});
  CHECK(frame_x[1] == A{0, 0, 1});
  const auto frame_y = compound_joint_frame({0, 1, 0});
  CHECK(frame_y[0] == A{1, 0, 0});
  CHECK(frame_y[1] == A{0, 0, -1});
  // An oblique normal: an orthonormal, right-handed frame.
  const double s = 1 / std::sqrt(3.0);
  const auto f = compound_joint_frame({s, -s, s});
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += f[a][k] * f[b][k];
      CHECK(d == Approx(a == b ? 1.0 : 0.0).margin(1e-15));
    }
  CHECK(f[0][1] * f[1][2] - f[0][2] * f[1][1] == Approx(f[2][0]).margin(1e-15));  // e1 x e2 = n
}

TEST_CASE("a planar joint loads from JSON as two slides and a turn", "[model][planar]") {
  const Model m = load_model(source_path("tests/data/models/planar_pendulum.json"));
  REQUIRE(m.joints.size() == 4);
  const char* names[] = {"base_x", "base_y", "base_theta", "swing"};
  for (int k = 0; k < 4; ++k) CHECK(m.joints[k].name == names[k]);
  CHECK(m.joints[0].type == JointType::prismatic);
  CHECK(m.joints[1].type == JointType::prismatic);
  CHECK(m.joints[2].type == JointType::revolute);
  CHECK(m.joints[0].axis == std::array<double, 3>{1, 0, 0});
  CHECK(m.joints[1].axis == std::array<double, 3>{0, 1, 0});
  CHECK(m.joints[2].axis == std::array<double, 3>{0, 0, 1});
  CHECK(m.joints[0].parent == "ground");
  CHECK(m.joints[0].child == "base_x_frame");
  CHECK(m.joints[1].parent == "base_x_frame");
  CHECK(m.joints[1].child == "base_y_frame");
  CHECK(m.joints[2].parent == "base_y_frame");
  CHECK(m.joints[2].child == "cart");
  CHECK(m.joints[0].q0 == 0.0);
  CHECK(m.joints[1].q0 == 0.5);
  CHECK(m.joints[2].q0 == 0.1);
  CHECK(m.joints[0].u0 == 0.3);
  CHECK(m.joints[2].u0 == -0.2);
  for (int k = 0; k < 3; ++k) CHECK(m.joints[k].where == "/joints/0");
  // The frames between the steps are massless bodies after the model's own.
  REQUIRE(m.bodies.size() == 4);
  CHECK(m.bodies[2].name == "base_x_frame");
  CHECK(m.bodies[3].name == "base_y_frame");
  CHECK(m.bodies[2].mass.value == 0.0);
  // The joint force names a step.
  REQUIRE(m.joint_efforts.size() == 1);
  CHECK(m.joint_efforts[0].joint == "base_theta");
}

TEST_CASE("a planar joint loads from URDF with its axis as the normal", "[model][planar][urdf]") {
  const TempModel urdf("urdf", ".urdf", R"(<robot name="r">
  <link name="base"/>
  <link name="sled"><inertial><mass value="2"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="floor" type="planar"><parent link="base"/><child link="sled"/>
    <origin xyz="0 0 0.5"/><axis xyz="1 0 0"/></joint>
</robot>)");
  const Model m = load_model(urdf.path);
  REQUIRE(m.joints.size() == 3);
  CHECK(m.joints[0].name == "floor_x");
  CHECK(m.joints[0].axis == std::array<double, 3>{0, 1, 0});
  CHECK(m.joints[1].axis == std::array<double, 3>{0, 0, 1});
  CHECK(m.joints[2].axis == std::array<double, 3>{1, 0, 0});
  CHECK(m.joints[0].origin_xyz[2].value == 0.5);
  CHECK(m.joints[1].origin_xyz[2].value == 0.0);
  for (const Joint& j : m.joints) CHECK(j.actuated);
}

TEST_CASE("bad planar joints: what they cannot carry, names they would take, references to them",
          "[model][planar][bad]") {
  {
    const TempModel f("initial", ".json", planar_json(R"(, "initial": {"q": [1, 2]})"));
    expect_model_error(f.path, "/joints/0/initial/q", "planar joint 'p' has 3 coordinates",
                       "give an array of 3 numbers, in the order of its steps (x, y, theta)");
  }
  {
    const TempModel f("one", ".json", planar_json(R"(, "initial": {"u": 1})"));
    expect_model_error(f.path, "/joints/0/initial/u", "planar joint 'p' has 3 coordinates", "array of 3");
  }
  {
    const TempModel f(
        "array", ".json",
        R"({"format": "kanegen-model", "version": 1, "name": "c", "bodies": [{"name": "b", "mass": 1}],
      "joints": [{"name": "h", "type": "prismatic", "parent": "ground", "child": "b", "initial": {"q": [1, 2, 3]}}]})");
    expect_model_error(f.path, "/joints/0/initial/q", "prismatic joint 'h' has one coordinate",
                       "give one number");
  }
  {
    const TempModel f("spring", ".json", planar_json(R"(, "spring": {"stiffness": 3})"));
    expect_model_error(f.path, "/joints/0/spring", "a spring on planar joint 'p'",
                       "remove it (a planar joint carries none), or build the motion from 'p_x', 'p_y' and "
                       "'p_theta' as separate joints");
  }
  {
    const TempModel f("damping", ".json", planar_json(R"(, "damping": 0.1)"));
    expect_model_error(f.path, "/joints/0/damping", "damping on planar joint 'p'", "remove it");
  }
  {
    const TempModel f("prescribed", ".json", planar_json(R"(, "prescribed": "t")"));
    expect_model_error(f.path, "/joints/0/prescribed", "a prescribed motion on planar joint 'p'",
                       "remove it");
  }
  {
    const TempModel f("axis", ".json", planar_json(R"(, "axis": [0, 0, 0])"));
    expect_model_error(f.path, "/joints/0/axis", "axis of planar joint 'p' has no direction",
                       "give the normal of the plane");
  }
  {
    const TempModel f("taken", ".json",
                      R"({"format": "kanegen-model", "version": 1, "name": "c",
      "bodies": [{"name": "b", "mass": 1, "inertia": {"ixx": 1, "iyy": 1, "izz": 1}}, {"name": "p_x_frame", "mass": 1}],
      "joints": [{"name": "p", "type": "planar", "parent": "ground", "child": "b"},
                 {"name": "f", "type": "revolute", "parent": "b", "child": "p_x_frame"}]})");
    expect_model_error(f.path, "/joints/0/name", "'p_x_frame' is already taken",
                       "rename the joint or the body named 'p_x_frame'");
  }
  {
    const TempModel f("output", ".json",
                      planar_json("", R"(, "outputs": [{"name": "a", "type": "joint", "joint": "p"}])"));
    expect_model_error(f.path, "/outputs/0/joint",
                       "output 'a' names planar joint 'p', which has 3 coordinates",
                       "name one of them: 'p_x', 'p_y' or 'p_theta'");
  }
  {
    const TempModel f(
        "effort", ".json",
        planar_json("", R"(, "forces": [{"name": "e", "type": "joint_effort", "joint": "p", "value": 1}])"));
    expect_model_error(f.path, "/forces/0/joint", "joint force 'e' names planar joint 'p'", "'p_theta'");
  }
}

namespace {

/// A JSON model with a joint "s" of `type` from the ground to body "b".
std::string joint_json(const std::string& type, const std::string& joint, const std::string& rest = "") {
  return R"({"format": "kanegen-model", "version": 1, "name": "ball_case",
    "bodies": [{"name": "b", "mass": 1, "inertia": {"ixx": 1, "iyy": 1, "izz": 1}}],
    "joints": [{"name": "s", "type": ")" +
         type + R"(", "parent": "ground", "child": "b")" + joint + "}]" + rest + "}";
}

}  // namespace

TEST_CASE("a free joint loads as three slides and a spherical joint, its initial values split among them",
          "[model][spherical]") {
  const TempModel f("free", ".json", joint_json("free", R"(, "origin": {"xyz": [0, 0, 1]},
      "initial": {"q": [1, 2, 3, 0.6, 0.8, 0, 0], "u": [4, 5, 6, 7, 8, 9]})"));
  const Model m = load_model(f.path);
  REQUIRE(m.joints.size() == 4);
  const std::vector<std::string> names{"s_x", "s_y", "s_z", "s"};
  for (std::size_t k = 0; k < 4; ++k) CHECK(m.joints[k].name == names[k]);
  CHECK(m.joints[0].axis == std::array<double, 3>{1, 0, 0});
  CHECK(m.joints[1].axis == std::array<double, 3>{0, 1, 0});
  CHECK(m.joints[2].axis == std::array<double, 3>{0, 0, 1});
  CHECK(m.joints[0].origin_xyz[2].value == 1.0);
  CHECK(m.joints[3].origin_xyz[2].value == 0.0);
  CHECK(joint_named(m, "s").type == JointType::spherical);
  CHECK(m.joints[3].parent == "s_z_frame");
  CHECK(m.joints[3].child == "b");
  CHECK(m.joints[0].q0 == 1.0);
  CHECK(m.joints[2].u0 == 6.0);
  CHECK(m.joints[3].step_q0 == std::vector<double>{0.6, 0.8, 0, 0});
  CHECK(m.joints[3].step_u0 == std::vector<double>{7, 8, 9});
}

TEST_CASE("URDF's floating joint is a free joint; spherical and free are no URDF types",
          "[model][spherical][urdf]") {
  const auto urdf = [](const std::string& type) {
    return R"(<robot name="r">
  <link name="base"/>
  <link name="box"><inertial><mass value="2"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type=")" +
           type + R"("><parent link="base"/><child link="box"/></joint>
</robot>)";
  };
  const TempModel floating("floating", ".urdf", urdf("floating"));
  const Model m = load_model(floating.path);
  REQUIRE(m.joints.size() == 4);
  CHECK(m.joints[3].name == "j");
  CHECK(m.joints[3].type == JointType::spherical);
  CHECK(m.joints[0].axis == std::array<double, 3>{1, 0, 0});  // not URDF's default axis (1, 0, 0) turned
  const TempModel spherical("spherical", ".urdf", urdf("spherical"));
  expect_model_error(spherical.path, "line 4: <joint name=\"j\">", "unknown URDF joint type 'spherical'",
                     "a spherical joint is for kanegen model files");
}

TEST_CASE("bad spherical and free joints: what they cannot carry, quaternions, loops, references",
          "[model][spherical][bad]") {
  {
    const TempModel f("unit", ".json", joint_json("spherical", R"(, "initial": {"q": [1, 1, 0, 0]})"));
    expect_model_error(f.path, "/joints/0/initial/q", "the quaternion of spherical joint has length 1.41",
                       "give a unit quaternion w, x, y, z");
  }
  {
    const TempModel f("count", ".json", joint_json("spherical", R"(, "initial": {"u": [1, 2, 3, 4]})"));
    expect_model_error(f.path, "/joints/0/initial/u", "spherical joint 's' has 3 speeds",
                       "give an array of 3 numbers, in the order wx, wy, wz");
  }
  {
    const TempModel f("free_count", ".json", joint_json("free", R"(, "initial": {"q": [0, 0, 0, 1]})"));
    expect_model_error(f.path, "/joints/0/initial/q", "free joint 's' has 7 coordinates",
                       "x, y, z, then the quaternion w, x, y, z");
  }
  {
    const TempModel f("axis", ".json", joint_json("spherical", R"(, "axis": [0, 0, 1])"));
    expect_model_error(f.path, "/joints/0/axis", "spherical joint 's' has no axis", "remove it");
  }
  {
    const TempModel f("spring", ".json", joint_json("spherical", R"(, "spring": {"stiffness": 3})"));
    expect_model_error(f.path, "/joints/0/spring", "a spring on spherical joint 's'",
                       "remove it (a spherical joint carries none)");
  }
  {
    const TempModel f("free_damping", ".json", joint_json("free", R"(, "damping": 0.1)"));
    expect_model_error(f.path, "/joints/0/damping", "damping on free joint 's'",
                       "or build the motion from 's_x', 's_y', 's_z' and 's' as separate joints");
  }
  {
    const TempModel f(
        "output", ".json",
        joint_json("spherical", "", R"(, "outputs": [{"name": "a", "type": "joint", "joint": "s"}])"));
    expect_model_error(f.path, "/outputs/0/joint", "output 'a' names spherical joint 's', which has several",
                       "give a point_position output");
  }
  {
    const TempModel f(
        "loop", ".json",
        joint_json("spherical", "", R"(, "loops": [{"name": "l", "type": "spherical", "body": "b",
        "point": [0, 0, 1], "body2": "ground", "point2": [0, 0, 1]}])"));
    expect_model_error(f.path, "/joints/0/type", "spherical joint 's' in a model with closed loops",
                       "build the motion from revolute and prismatic joints, or open the loop");
  }
}
