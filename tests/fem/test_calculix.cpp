// SPDX-License-Identifier: GPL-2.0-or-later
// Spatial frames against CalculiX 2.20 (B31 beams; results and inputs in
// data/, written by ccx/make_reference.py, so this suite needs no CalculiX).
// CalculiX expands B31 into bricks that do not warp, so its square section has
// the torsion constant Ip = a^4 / 6; the models here use the same J (the
// cantilever's torsion mode checks that against the closed form).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "fem_test_support.hpp"

using namespace kanegen::fem;

namespace {

struct Reference {
  std::map<std::string, std::vector<double>> params;  // "# key values..." lines
  std::vector<double> omega;                          // rad/s, by mode
};

Reference read_reference(const std::string& name) {
  const std::string path = std::string(KANEGEN_FEM_DATA_DIR) + "/" + name + "_ccx.txt";
  std::ifstream in(path);
  REQUIRE(in.good());
  Reference ref;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    if (line.rfind("# ", 0) == 0) {
      std::string hash, key;
      words >> hash >> key;
      std::vector<double> values;
      for (double v; words >> v;) values.push_back(v);
      if (!values.empty()) ref.params[key] = values;
    } else if (!line.empty()) {
      int mode;
      double omega;
      words >> mode >> omega;
      REQUIRE(mode == static_cast<int>(ref.omega.size()) + 1);
      ref.omega.push_back(omega);
    }
  }
  return ref;
}

/// Hermite elements per leg here; the CalculiX meshes are much finer (B31 is linear).
constexpr int kElementsPerLeg = 20;

/// The frame the reference describes: legs from the origin, clamped there, square section with J = Ip.
Body frame_of(const Reference& ref) {
  BeamProperties p;
  p.kind = BeamKind::kSpatial;
  const double a = ref.params.at("side")[0];
  p.section.A = a * a;
  p.section.Iy = p.section.Iz = a * a * a * a / 12.0;
  p.section.J = p.section.Iy + p.section.Iz;
  p.material = Material::isotropic(ref.params.at("E")[0], ref.params.at("nu")[0], ref.params.at("rho")[0]);
  Body body(spatial_layout());
  int node = body.add_node(Eigen::Vector3d::Zero());
  for (int leg = 0; ref.params.count("leg" + std::to_string(leg)); ++leg) {
    const std::vector<double>& l = ref.params.at("leg" + std::to_string(leg));
    node = add_beam_run(body, node, Eigen::Vector3d(l[0], l[1], l[2]), kElementsPerLeg, p);
  }
  return body;
}

void compare(const std::string& name) {
  const Reference ref = read_reference(name);
  REQUIRE(ref.omega.size() >= 10);
  const Body body = frame_of(ref);
  const Eigen::VectorXd omega =
      fem_test::frequencies(support_constraint(body, Support::kClamped), body.mass(), body.stiffness());
  for (std::size_t i = 0; i < ref.omega.size(); ++i) {
    INFO(name << " mode " << i + 1 << ": kanegen " << omega[i] << " rad/s, CalculiX " << ref.omega[i]);
    CHECK(std::abs(fem_test::rel_error(omega[static_cast<int>(i)], ref.omega[i])) < 1e-2);
  }
}

}  // namespace

TEST_CASE("calculix: spatial L-frame natural frequencies within 1 %", "[calculix]") { compare("l_frame"); }

TEST_CASE("calculix: straight cantilever, bending pairs and torsion within 1 %", "[calculix]") {
  compare("cantilever");
  // CalculiX's torsion mode is at the closed form for J = Ip (so not Saint-Venant's 0.1406 a^4).
  const Reference ref = read_reference("cantilever");
  const double G = ref.params.at("E")[0] / (2.0 * (1.0 + ref.params.at("nu")[0]));
  const double torsion = M_PI / 2.0 * std::sqrt(G / ref.params.at("rho")[0]) / ref.params.at("leg0")[0];
  int near = 0;
  for (double w : ref.omega) near += std::abs(fem_test::rel_error(w, torsion)) < 1e-3;
  CHECK(near == 1);
}
