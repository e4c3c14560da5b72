// SPDX-License-Identifier: GPL-2.0-or-later
// The .inp mesh reader and the body built from a mesh (issue 18): a file Gmsh
// wrote, records continued over lines, sets with GENERATE, and bad meshes
// (data/bad_meshes/) ending in one clear error naming file, line and element.
#include <catch2/catch.hpp>
#include <sstream>
#include <string>

#include "fem/mesh_body.hpp"
#include "model/model_error.hpp"

using namespace kanegen::fem;
using kanegen::model::ModelError;

namespace {

const ContinuumMaterial kSteel{2.1e11, 0.3, 7850.0};

std::string data(const std::string& name) { return std::string(KANEGEN_FEM_DATA_DIR) + "/" + name; }

InpMesh read_text(const std::string& text) {
  std::istringstream in(text);
  return read_inp_mesh(in, "inline.inp");
}

/// The message of the ModelError that reading (and building a body of) the bad mesh throws.
std::string error_of(const std::string& name) {
  try {
    build_mesh_body(read_inp_mesh_file(data("bad_meshes/" + name)), kSteel, 0.01);
  } catch (const ModelError& e) {
    return e.what();
  }
  FAIL("no error for " << name);
  return "";
}

}  // namespace

TEST_CASE("inp mesh: a file Gmsh wrote reads, with its node and element sets", "[inp]") {
  // bar_c3d8.inp: `gmsh -3 -format inp` of bar_c3d8.geo, 16 x 3 x 2 hexahedra; Gmsh also writes
  // the ROOT face as 6 CPS4 elements, which the body leaves out (it takes the highest dimension).
  const InpMesh mesh = read_inp_mesh_file(data("bar_c3d8.inp"));
  CHECK(mesh.nodes.size() == 17 * 4 * 3);
  CHECK(mesh.elements.size() == 96 + 6);
  CHECK(mesh.node_set("root").size() == 12);  // names are case-insensitive
  CHECK(mesh.element_set("BAR").size() == 96);
  for (int id : mesh.node_set("ROOT")) CHECK(mesh.nodes[mesh.node_index(id)].position.x() == 0.0);
  const MeshBody mb = build_mesh_body(mesh, kSteel);
  CHECK(mb.body.num_nodes() == 204);
  CHECK(mb.body.num_elements() == 96);
  CHECK(mb.body.layout() == solid_layout());
  CHECK(mb.clamped(mesh, "ROOT").num_free() == 3 * (204 - 12));
  // The volume and the mass are the bar's: 0.2 x 0.02 x 0.012 m.
  double volume = 0.0;
  for (int e = 0; e < mb.body.num_elements(); ++e)
    volume += static_cast<const ContinuumElement&>(*mb.body.element(e).element).volume();
  CHECK(volume == Approx(0.2 * 0.02 * 0.012).epsilon(1e-12));
  // The faces alone, by their element set, would be a plane body, but they lie in the y-z plane.
  CHECK_THROWS_WITH(
      build_mesh_body(mesh, kSteel, 0.001, "ROOT"),
      Catch::Contains("line 210, element 1: plane element: its nodes are not in one plane z = const"));
}

TEST_CASE("inp mesh: continued records, GENERATE, comments, other keywords", "[inp]") {
  const InpMesh c3d20 = read_inp_mesh_file(data("bar_c3d20.inp"));
  CHECK(c3d20.elements.size() == 16);
  for (const MeshElement& e : c3d20.elements) CHECK(e.nodes.size() == 20);
  CHECK(c3d20.element_set("EALL").size() == 16);  // *ELSET, GENERATE
  const InpMesh mesh = read_text(
      "** a comment\n*Heading\n some title, with a comma\n*node, nset=Left\n1, 0., 0.\n2, 1., 0.\n"
      "3, 1., 1.\n4, 0., 1.\n5, 2., 0.\n6, 2., 1.\n*Element, type=cps4, elset=A\n1, 1, 2,\n 3, 4\n"
      "2, 2, 5, 6, 3\n*NSET, NSET=ODD, GENERATE\n1, 5, 2\n*NSET, NSET=BOTH\nODD, 6\n"
      "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n");
  CHECK(mesh.elements.size() == 2);
  CHECK(mesh.elements[0].nodes == std::vector<int>{1, 2, 3, 4});
  CHECK(mesh.elements[0].line == 12);
  CHECK(mesh.node_set("odd") == std::vector<int>{1, 3, 5});
  CHECK(mesh.node_set("BOTH") == std::vector<int>{1, 3, 5, 6});
  CHECK(mesh.node_set("LEFT").size() == 6);
  const MeshBody mb = build_mesh_body(mesh, kSteel, 0.01);
  CHECK(mb.body.layout() == plane_layout());
  CHECK(mb.node_set_dofs(mesh, "ODD").size() == 6);
}

TEST_CASE("inp mesh: bad meshes get an error naming the file, the line and the element", "[inp]") {
  struct Case {
    const char* file;
    std::vector<const char*> says;
  };
  const Case cases[] = {
      {"unknown_type.inp",
       {"unknown_type.inp: line 7:", "unknown element type 'CPS4R'",
        "CPS4, CPS8, C3D8, C3D20, C3D10, C3D6, C3D15"}},
      {"missing_node.inp", {"missing_node.inp: line 11:", "element 2 refers to node 7", "does not define"}},
      {"duplicate_node.inp", {"duplicate_node.inp: line 6:", "node 3 is defined twice (first on line 5)"}},
      {"duplicate_element.inp",
       {"duplicate_element.inp: line 11:", "element 1 is defined twice (first on line 10)"}},
      {"inverted.inp",
       {"inverted.inp: line 11, element 2:", "CPS4 element 2 is inverted", "det J = -", "counter-clockwise"}},
      {"short_element.inp", {"short_element.inp: line 12:", "element 1 has 7 nodes, a C3D8 has 8"}},
      {"bad_number.inp", {"bad_number.inp: line 4:", "'1.0.0' is not a coordinate"}},
      {"set_unknown_node.inp", {"set_unknown_node.inp: line 10:", "node set ROOT lists node 5"}},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.file);
    INFO(message);
    CHECK(message.find('\n') == std::string::npos);
    for (const char* part : c.says) CHECK(message.find(part) != std::string::npos);
  }
  // A node set or element set the mesh does not have, named with the sets it has.
  const InpMesh mesh = read_inp_mesh_file(data("bar_c3d8.inp"));
  CHECK_THROWS_WITH(mesh.node_set("CLAMP"),
                    Catch::Contains("bar_c3d8.inp: node set CLAMP: the mesh has no node set 'CLAMP'") &&
                        Catch::Contains("(the file has BAR, ROOT)"));
  CHECK_THROWS_WITH(build_mesh_body(mesh, kSteel, 1.0, "HUB"), Catch::Contains("no element set 'HUB'"));
  CHECK_THROWS_WITH(read_inp_mesh_file(data("bad_meshes/none.inp")), Catch::Contains("cannot open"));
  CHECK_THROWS_WITH(read_text("1, 0, 0\n"),
                    Catch::Contains("inline.inp: line 1: data line before any keyword"));
  CHECK_THROWS_WITH(read_text("*NODE\n1, 0, 0\n"), Catch::Contains("the file has no elements"));
  CHECK_THROWS_WITH(read_text("*NODE\n1, 0, 0\n*ELEMENT, TYPE=CPS4\n1, 1, 1, 1, 1, 1\n"),
                    Catch::Contains("line 4: element 1 has more than 4 nodes"));
  CHECK_THROWS_WITH(read_text("*NODE\n1,0,0\n*ELEMENT, TYPE=CPS4\n1, 1,1,1,1\n*NSET, NSET=A\nB\n"),
                    Catch::Contains("line 6: set 'B' is not defined before this line"));
  CHECK_THROWS_WITH(read_text("*NODE\n-1, 0, 0\n"), Catch::Contains("'-1' is not a node id"));
  CHECK_THROWS_WITH(read_text("*NSET, NSET=A, GENERATE\n1, 2000000000, 1\n"),
                    Catch::Contains("line 2: GENERATE would list more than 10000000 ids"));
  CHECK_THROWS_WITH(read_text("*INCLUDE, INPUT=x.inp\n"), Catch::Contains("*INCLUDE is not supported"));
  // A degenerate element (all nodes at one point) is refused as well, with its line.
  CHECK_THROWS_WITH(
      build_mesh_body(read_text("*NODE\n1,0,0\n*ELEMENT, TYPE=CPS4\n1, 1,1,1,1\n"), kSteel, 0.01),
      Catch::Contains("inline.inp: line 4, element 1: CPS4 element 1 is inverted"));
}
