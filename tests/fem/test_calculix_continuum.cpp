// SPDX-License-Identifier: GPL-2.0-or-later
// Plane-stress plates and solid bars against CalculiX 2.20 on the same meshes
// and element types (CPS4, CPS8, C3D8 from Gmsh, C3D20; C3D10, C3D6, C3D15
// and the solid rod in C3D10, all from Gmsh), clamped at the node
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

#include "fem/craig_bampton.hpp"
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

std::string data_mesh(const std::string& name) {
  return std::string(KANEGEN_FEM_DATA_DIR) + "/" + name + ".inp";
}

MeshBody reference_body(const Reference& ref, const InpMesh& mesh) {
  const ContinuumMaterial material{ref.params.at("E"), ref.params.at("nu"), ref.params.at("rho")};
  const double thickness = ref.params.count("thickness") ? ref.params.at("thickness") : 1.0;
  return build_mesh_body(mesh, material, thickness);
}

/// The first 12 clamped (at the node set `clamp`) and the first 12 elastic free-free frequencies within a
/// relative tolerance. mesh_path: the mesh to read, if not the reference's own in data/ (the same mesh
/// written by another tool, or a shipped one).
void compare(const std::string& name, double tolerance, const std::string& mesh_path = "",
             const std::string& clamp = "ROOT") {
  const Reference ref = read_reference(name);
  REQUIRE(ref.omega.at("clamped").size() == 12);
  REQUIRE(ref.omega.at("free").size() == 12);
  const InpMesh mesh = read_inp_mesh_file(mesh_path.empty() ? data_mesh(name) : mesh_path);
  const MeshBody mb = reference_body(ref, mesh);
  const Eigen::MatrixXd M = mb.body.mass(), K = mb.body.stiffness();
  const Constraint root = mb.clamped(mesh, clamp);
  const Eigen::VectorXd clamped = modal_analysis(root.reduce(M), root.reduce(K)).omega;
  const Eigen::VectorXd free = modal_analysis(M, K).omega;
  const int rigid = mb.body.dofs_per_node() == 2 ? 3 : 6;  // in-plane rigid motions of a plate
  // Zero to rounding: omega^2 within 1e-8 of the first elastic one (the stiff rod's rigid modes come out
  // near 0.05 rad/s beside 2242 rad/s, as K's entries are 1e12 times M's).
  for (int i = 0; i < rigid; ++i) CHECK(free[i] < 1e-4 * free[rigid]);
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
  compare("bar_c3d20", 1e-5, data_mesh("bar_c3d20_gmsh"));
}

TEST_CASE("calculix: solid bar, C3D10 meshed by Gmsh, clamped and free, 12 modes to 1e-5", "[calculix]") {
  // CalculiX integrates C3D10 with 4 points, the mass too (not exact for its quartic integrand): kanegen's
  // row does the same, so the frequencies agree to the printed digits.
  compare("bar_c3d10", 1e-5);
}

TEST_CASE("calculix: solid bar, C3D6 wedges meshed by Gmsh, clamped and free, 12 modes to 1e-5",
          "[calculix]") {
  compare("bar_c3d6", 1e-5);
}

TEST_CASE("calculix: solid bar, C3D15 wedges meshed by Gmsh, clamped and free, 12 modes to 1e-5",
          "[calculix]") {
  compare("bar_c3d15", 1e-5);
}

TEST_CASE("calculix: the solid rod in C3D10 (Gmsh), clamped at its big end and free, 12 modes to 1e-5",
          "[calculix]") {
  // Issue 38 asks for 0.5 %; the same elements as CalculiX's agree to its printed digits.
  compare("solid_slider_crank_c3d10", 1e-5, "", "BIG_END");
}

TEST_CASE(
    "calculix: the solid slider-crank's rod (models/, C3D20 from Gmsh), clamped at its big end, 12 modes "
    "to 1e-5",
    "[calculix]") {
  compare("solid_slider_crank", 1e-5, std::string(KANEGEN_MODELS_DIR) + "/solid_slider_crank.inp", "BIG_END");
}

TEST_CASE(
    "calculix: the solid rod by Craig-Bampton (small-end bore as interface, 8 fixed-interface modes) "
    "keeps CalculiX's first clamped-free frequencies",
    "[calculix]") {
  // The basis of models/solid_slider_crank.json: the 6 rigid motions of the small-end bore (where the loop
  // to the slider acts) and 8 modes with that bore held. A Ritz basis, so each frequency is at or above
  // the full mesh's; its interface statics are exact, so the free small end's bending pairs and the
  // axial mode, which the loop loads, come out close.
  const Reference ref = read_reference("solid_slider_crank");
  const InpMesh mesh = read_inp_mesh_file(std::string(KANEGEN_MODELS_DIR) + "/solid_slider_crank.inp");
  const MeshBody mb = reference_body(ref, mesh);
  std::vector<int> small_end;
  for (int id : mesh.node_set("SMALL_END")) small_end.push_back(mb.node_of.at(id));
  const CraigBamptonBasis cb = craig_bampton(mb.body, mb.clamped(mesh, "BIG_END"), {small_end}, 8);
  REQUIRE(cb.basis.cols() == 14);
  const Eigen::MatrixXd M = cb.basis.transpose() * mb.body.mass() * cb.basis;
  const Eigen::MatrixXd K = cb.basis.transpose() * mb.body.stiffness() * cb.basis;
  const Eigen::VectorXd omega = modal_analysis(M, K).omega;
  const std::vector<double> tolerance = {1e-3, 1e-3, 1e-3, 1e-3, 1e-2, 1e-2};
  for (std::size_t i = 0; i < tolerance.size(); ++i) {
    const double c = ref.omega.at("clamped")[i];
    INFO("mode " << i + 1 << ": Craig-Bampton " << omega[i] << " CalculiX " << c << " rad/s");
    CHECK(omega[i] > c * (1 - 1e-6));
    CHECK(omega[i] / c - 1.0 < tolerance[i]);
  }
}
