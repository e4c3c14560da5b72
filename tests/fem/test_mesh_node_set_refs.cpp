// SPDX-License-Identifier: GPL-2.0-or-later
// Loops, point forces and node outputs on a mesh body's node sets (issue 18):
// each set becomes one interface of the body, shared by everything that
// names it and kept by Craig-Bampton; and the errors of bad references,
// which name the model file, the JSON pointer and the fix.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "fem/elastic_model.hpp"
#include "model/load.hpp"
#include "model_text.hpp"

namespace {

using namespace kanegen;

const std::string kData = KANEGEN_FEM_DATA_DIR;

const fem::ShapeSampler kNoShapes = [](const std::string&, const std::map<std::string, double>&,
                                       const std::vector<double>&, std::vector<double>&,
                                       std::vector<double>&) {};

/// The slender CPS8 bar (node sets ROOT, TIP, BAR) with CORNER, one node
/// of its tip edge, added: a copy in the temporary directory while the
/// tests run.
struct MeshWithCorner {
  std::string path = (std::filesystem::temp_directory_path() /
                      ("kanegen_test_corner_" + std::to_string(::getpid()) + ".inp"))
                         .string();
  MeshWithCorner() {
    std::ofstream(path) << std::ifstream(kData + "/slender_cps8.inp").rdbuf() << "*NSET,NSET=CORNER\n2\n";
  }
  ~MeshWithCorner() { std::remove(path.c_str()); }
};

/// A model of the bar on a hub (clamped on ROOT, `reduction`), a rigid
/// link on the ground and a rigid block, with the given "loops", "forces"
/// and "outputs" (JSON arrays).
model::Model load_bar(const std::string& loops, const std::string& forces, const std::string& outputs,
                      const std::string& reduction = "modal") {
  static const MeshWithCorner corner;
  const std::string& mesh = corner.path;
  return kanegen_test::load_model_text(
      R"({"format": "kanegen-model", "version": 1, "name": "bar", "bodies": [
    {"name": "hub", "mass": 1, "inertia": {"ixx": 1e-3, "iyy": 1e-3, "izz": 1e-3}},
    {"name": "bar", "flexible": {"mesh": {"file": ")" +
          mesh + R"(", "element_set": "BAR", "thickness": 0.002, "clamped_set": "ROOT", "reduction": ")" +
          reduction + R"("},
      "material": {"E": 2.1e11, "poisson": 0.3, "density": 7800}, "modes": 2}},
    {"name": "beam", "flexible": {"length": 0.2, "elements": 2, "section": {"A": 1e-4, "Iz": 1e-9},
      "material": {"E": 2.1e11, "density": 7800}, "modes": 1}},
    {"name": "block", "mass": 0.1, "inertia": {"ixx": 1e-4, "iyy": 1e-4, "izz": 1e-4}}],
  "joints": [{"name": "spin", "type": "revolute", "parent": "ground", "child": "hub"},
             {"name": "mount", "type": "fixed", "parent": "hub", "child": "bar"},
             {"name": "swing", "type": "revolute", "parent": "ground", "child": "beam"},
             {"name": "rock", "type": "revolute", "parent": "ground", "child": "block",
              "origin": {"xyz": [0.4, 0.3, 0]}}],
  "loops": )" +
          loops + R"(, "forces": )" + forces + R"(, "outputs": )" + outputs + "}",
      "mesh_node_set_refs");
}

fem::ElasticModel bar_of(const model::Model& m) {
  return fem::build_elastic_model(m.bodies[1], m.source_file, kNoShapes);
}

const std::string kTipLoop =
    R"([{"name": "pin", "type": "revolute", "planar": true, "body": "block", "point": [0, -0.3, 0],
         "body2": "bar", "node_set2": "TIP"}])";

}  // namespace

TEST_CASE("a node set named by a loop, a force and an output is one interface of the mesh body",
          "[mesh_node_sets]") {
  const model::Model m =
      load_bar(kTipLoop, R"([{"name": "load", "body": "bar", "node_set": "TIP", "force": [0, -1, 0]},
                             {"name": "mid", "body": "bar", "node_set": "BAR", "force": [1, 0, 0]}])",
               R"([{"name": "tip", "type": "node_displacement", "body": "bar", "node_set": "TIP"}])");
  REQUIRE(m.bodies[1].elastic.mesh.interfaces.size() == 2);
  CHECK(m.bodies[1].elastic.mesh.interfaces[0].node_set == "TIP");
  CHECK(m.bodies[1].elastic.mesh.interfaces[0].where == "/forces/0/node_set");  // forces come before loops
  CHECK(m.bodies[1].elastic.mesh.interfaces[0].rotation_where.empty());  // a planar hinge needs no rotation
  CHECK(m.loops[0].node2 == 0);
  CHECK(m.forces[0].node == 0);
  CHECK(m.forces[1].node == 1);
  CHECK(m.outputs[0].node == 0);
  const fem::ElasticModel bar = bar_of(m);
  REQUIRE(bar.interfaces.size() == 2);
  CHECK((bar.point_position(0) - Eigen::Vector3d(0.4, 0, 0)).norm() < 1e-12);  // the tip edge's centroid
  CHECK((bar.point_position(1) - Eigen::Vector3d(0.2, 0, 0)).norm() < 1e-12);  // the whole bar's
}

TEST_CASE("Craig-Bampton keeps a node set that only a loop or a force names as an interface",
          "[mesh_node_sets]") {
  const model::Model by_loop = load_bar(kTipLoop, "[]", "[]", "craig-bampton");
  CHECK(bar_of(by_loop).reduced.names.size() == 3 + 2);  // TIP's u_x, u_y, theta_z, then 2 modes
  const model::Model by_force =
      load_bar("[]", R"([{"name": "load", "body": "bar", "node_set": "TIP", "force": [0, -1, 0]}])", "[]",
               "craig-bampton");
  const fem::ElasticModel bar = bar_of(by_force);
  REQUIRE(bar.reduced.names.size() == 5);
  // The constraint modes move the interface rigidly, each by one motion alone (scaled to unit modal
  // mass): statics there are exact. The second is its u_y.
  const Eigen::MatrixXd t = bar.point_translation(0);
  CHECK(t(1, 1) > 0);
  CHECK(std::abs(t(0, 1)) + std::abs(t(2, 1)) + std::abs(t(1, 0)) + std::abs(t(1, 2)) < 1e-9 * t(1, 1));
  CHECK(bar.reduced.mass(1, 1) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("a one-node set serves a force, an output and a point joint, not a rotation", "[mesh_node_sets]") {
  const model::Model m =
      load_bar("[]", R"([{"name": "load", "body": "bar", "node_set": "CORNER", "force": [0, -1, 0]}])",
               R"([{"name": "corner", "type": "node_displacement", "body": "bar", "node_set": "CORNER"}])");
  const fem::ElasticModel bar = bar_of(m);
  CHECK((bar.point_position(0) - Eigen::Vector3d(0.4, -0.005, 0)).norm() < 1e-12);
  CHECK(bar.point_rotation(0).norm() == 0.0);  // undetermined, and used by nothing

  const model::Model slider =
      load_bar(R"([{"name": "track", "type": "slider", "planar": true, "body": "bar", "node_set": "CORNER",
                    "axis": [1, 0, 0], "body2": "block"}])",
               "[]", "[]");
  CHECK_THROWS_WITH(bar_of(slider), Catch::Contains(slider.source_file) &&
                                        Catch::Contains("/loops/0/node_set: node set CORNER") &&
                                        Catch::Contains("single node") &&
                                        Catch::Contains("two or more nodes"));
}

TEST_CASE("bad node-set references are refused with the place and the fix", "[mesh_node_sets]") {
  const auto refused = [](const std::string& loops, const std::string& forces, const std::string& outputs,
                          const std::string& place, const std::string& problem, const std::string& fix) {
    INFO(place << ": " << problem);
    CHECK_THROWS_WITH(load_bar(loops, forces, outputs),
                      Catch::Contains(place) && Catch::Contains(problem) && Catch::Contains(fix));
  };
  SECTION("on a rigid body") {
    refused("[]", R"([{"name": "f", "body": "block", "node_set": "TIP", "force": [0, 1, 0]}])", "[]",
            "/forces/0/node_set", "names node set 'TIP' of 'block', which is not a mesh body (it is rigid)",
            "give a point of the body frame");
  }
  SECTION("on a beam") {
    refused(R"([{"name": "pin", "type": "spherical", "body": "beam", "node_set": "TIP", "body2": "block"}])",
            "[]", "[]", "/loops/0/node_set", "which is not a mesh body (it is a beam)",
            "\"node\": 3, or \"tip\"");
  }
  SECTION("on the ground") {
    refused(R"([{"name": "pin", "type": "spherical", "body": "bar", "node_set": "TIP", "body2": "ground",
                 "node_set2": "TIP"}])",
            "[]", "[]", "/loops/0/node_set2", "the ground has no node sets", "remove \"node_set2\"");
  }
  SECTION("with a point or a node") {
    refused("[]",
            R"([{"name": "f", "body": "bar", "point": [0, 0, 0], "node_set": "TIP", "force": [0, 1, 0]}])",
            "[]", "/forces/0/node_set", "both 'point' and 'node_set' given", "node set of a mesh body");
    refused(R"([{"name": "pin", "type": "spherical", "body": "block", "body2": "bar", "node2": 3,
                 "node_set2": "TIP"}])",
            "[]", "[]", "/loops/0/node_set2", "both 'node2' and 'node_set2' given", "give one");
    refused("[]", "[]",
            R"([{"name": "o", "type": "node_displacement", "body": "bar", "node": 1, "node_set": "TIP"}])",
            "/outputs/0/node_set", "both 'node' and 'node_set' given", "give one");
  }
  SECTION("a node of a mesh body, by index") {
    refused("[]", R"([{"name": "f", "body": "bar", "node": 3, "force": [0, 1, 0]}])", "[]", "/forces/0/node",
            "which is a mesh body", "name a node set of its mesh instead");
  }
  SECTION("a section resultant, which a mesh has not") {
    refused("[]", "[]", R"([{"name": "o", "type": "axial_force", "body": "bar", "node_set": "TIP"}])",
            "/outputs/0/node_set", "section resultant", "node_displacement");
  }
}

TEST_CASE("a node set the mesh does not have: the place that names it and the sets there are",
          "[mesh_node_sets]") {
  const model::Model m =
      load_bar("[]", R"([{"name": "load", "body": "bar", "node_set": "TOP", "force": [0, -1, 0]}])", "[]");
  CHECK_THROWS_WITH(bar_of(m), Catch::Contains(m.source_file) && Catch::Contains("/forces/0/node_set") &&
                                   Catch::Contains("no node set 'TOP'") &&
                                   Catch::Contains("BAR, CORNER, ROOT, TIP"));
}

TEST_CASE("a solid's node set on a line has no rotation: refused where a loop turns with it",
          "[mesh_node_sets]") {
  const std::string models = std::string(KANEGEN_FEM_DATA_DIR) + "/../../data/models/";
  const auto load = [&](const std::string& loop) {
    return kanegen_test::load_model_text(
        R"({"format": "kanegen-model", "version": 1, "name": "bar", "bodies": [
      {"name": "bar", "flexible": {"mesh": {"file": ")" +
            models + R"(tip_bar_c3d8.inp", "element_set": "BAR", "clamped_set": "ROOT"},
        "material": {"E": 2.1e11, "poisson": 0.3, "density": 7800}, "modes": 2}},
      {"name": "block", "mass": 0.1, "inertia": {"ixx": 1e-4, "iyy": 1e-4, "izz": 1e-4}}],
    "joints": [{"name": "spin", "type": "revolute", "parent": "ground", "child": "bar"},
               {"name": "rock", "type": "revolute", "parent": "ground", "child": "block"}],
    "loops": [)" +
            loop + "]}",
        "mesh_node_set_solid");
  };
  const model::Model hinge = load(
      R"({"name": "h", "type": "revolute", "body": "block", "body2": "bar", "node_set2": "TIPEDGE", "axis": [0, 0, 1]})");
  CHECK_THROWS_WITH(fem::build_elastic_model(hinge.bodies[0], hinge.source_file, kNoShapes),
                    Catch::Contains("/loops/0/node_set2") && Catch::Contains("lie on a line") &&
                        Catch::Contains("not all on one line"));
  const model::Model ball = load(
      R"({"name": "b", "type": "spherical", "body": "block", "body2": "bar", "node_set2": "TIPCORNER"})");
  const fem::ElasticModel bar = fem::build_elastic_model(ball.bodies[0], ball.source_file, kNoShapes);
  CHECK((bar.point_position(0) - Eigen::Vector3d(0.2, -0.01, -0.01)).norm() < 1e-12);
}
