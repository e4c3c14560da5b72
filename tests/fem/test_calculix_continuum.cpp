// SPDX-License-Identifier: GPL-2.0-or-later
// Plane-stress plates and solid bars against CalculiX 2.20 on the same meshes
// and element types (CPS4, CPS8, C3D8 from Gmsh, C3D20), clamped at the node
// set ROOT and free-free: meshes and results in data/, written by
// ccx/make_solid_reference.py, so this suite needs no CalculiX. The solids are
// the same elements as CalculiX's and agree to its 7 printed digits (checked to
// 1e-5); CalculiX computes plane stress on a layer of 3D elements, whose free
// faces are a little stiffer than exact plane stress (up to 0.28 % here).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "fem/mesh_body.hpp"
#include "fem/modal.hpp"

using namespace kanegen::fem;

namespace {

struct Reference {
  std::map<std::string, double> params;              // "# key value" lines
  std::map<std::string, std::vector<double>> omega;  // by support: rad/s, in mode order
};

Reference read_reference(const std::string& name) {
  std::ifstream in(std::string(KANEGEN_FEM_DATA_DIR) + "/" + name + "_ccx.txt");
  REQUIRE(in.good());
  Reference ref;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    if (line.rfind("# ", 0) == 0) {
      std::string hash, key;
      double value;
      if (words >> hash >> key >> value) ref.params[key] = value;
    } else if (!line.empty()) {
      std::string support;
      int mode;
      double omega;
      REQUIRE(static_cast<bool>(words >> support >> mode >> omega));
      ref.omega[support].push_back(omega);
    }
  }
  return ref;
}

/// The first 12 clamped and the first 12 elastic free-free frequencies within a relative tolerance.
/// mesh: the mesh to read, if not the reference's own (the same mesh written by another tool).
void compare(const std::string& name, double tolerance, const std::string& mesh_name = "") {
  const Reference ref = read_reference(name);
  REQUIRE(ref.omega.at("clamped").size() == 12);
  REQUIRE(ref.omega.at("free").size() == 12);
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_FEM_DATA_DIR) + "/" +
                                          (mesh_name.empty() ? name : mesh_name) + ".inp");
  const ContinuumMaterial material{ref.params.at("E"), ref.params.at("nu"), ref.params.at("rho")};
  const double thickness = ref.params.count("thickness") ? ref.params.at("thickness") : 1.0;
  const MeshBody mb = build_mesh_body(mesh, material, thickness);
  const Eigen::MatrixXd M = mb.body.mass(), K = mb.body.stiffness();
  const Constraint root = mb.clamped(mesh, "ROOT");
  const Eigen::VectorXd clamped = modal_analysis(root.reduce(M), root.reduce(K)).omega;
  const Eigen::VectorXd free = modal_analysis(M, K).omega;
  const int rigid = mb.body.dofs_per_node() == 2 ? 3 : 6;  // in-plane rigid motions of a plate
  for (int i = 0; i < rigid; ++i) CHECK(free[i] < 1e-5 * free[rigid]);
  for (int i = 0; i < 12; ++i) {
    const double c = ref.omega.at("clamped")[i], f = ref.omega.at("free")[i];
    INFO(name << " mode " << i + 1 << ": clamped kanegen " << clamped[i] << " CalculiX " << c
              << " rad/s; free kanegen " << free[rigid + i] << " CalculiX " << f);
    CHECK(std::abs(clamped[i] / c - 1.0) < tolerance);
    CHECK(std::abs(free[rigid + i] / f - 1.0) < tolerance);
  }
}

}  // namespace

TEST_CASE("calculix: plane-stress plate, CPS4, clamped and free, 12 modes within 0.5 %", "[calculix]") {
  compare("plate_cps4", 5e-3);
}

TEST_CASE("calculix: plane-stress plate, CPS8, clamped and free, 12 modes within 0.5 %", "[calculix]") {
  compare("plate_cps8", 5e-3);
}

TEST_CASE("calculix: solid bar, C3D8 meshed by Gmsh, clamped and free, 12 modes to 1e-5", "[calculix]") {
  compare("bar_c3d8", 1e-5);
}

TEST_CASE("calculix: solid bar, C3D20, clamped and free, 12 modes to 1e-5", "[calculix]") {
  compare("bar_c3d20", 1e-5);
}

TEST_CASE("calculix: the C3D20 bar meshed by Gmsh has CalculiX's frequencies of the same mesh",
          "[calculix]") {
  // Gmsh numbers nodes and elements its own way, and writes its ROOT faces as CPS8: what must agree is
  // the element node order, which the reference's frequencies check to 1e-6.
  compare("bar_c3d20", 1e-5, "bar_c3d20_gmsh");
}
