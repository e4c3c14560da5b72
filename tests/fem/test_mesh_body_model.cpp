// SPDX-License-Identifier: GPL-2.0-or-later
// Mesh bodies in model files (issue 18): a slender plane-stress bar of CPS8
// elements, clamped on its root node set and reduced to its first modes,
// against the Euler-Bernoulli beam elements of the same section (an
// independent element family); and the errors of bad mesh references.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "fem/elastic_model.hpp"
#include "model/load.hpp"
#include "model_text.hpp"

namespace {

using namespace kanegen;

const std::string kData = KANEGEN_FEM_DATA_DIR;
constexpr double kLength = 0.4, kHeight = 0.01, kThickness = 0.002, kE = 2.1e11, kNu = 0.3, kRho = 7800;

/// A one-body model whose flexible body is `flexible` (JSON), written to a temporary file and loaded.
model::Model load_with(const std::string& flexible, const std::string& tip_joint = "") {
  // A rigid body on the bar: in its frame unless tip_joint (its joint's extra keys) says where.
  return kanegen_test::load_model_text(R"({"format": "kanegen-model", "version": 1, "name": "bar", "bodies": [
    {"name": "bar", "flexible": )" + flexible +
                                           R"(}, {"name": "tip_body", "mass": 0.1}],
    "joints": [{"name": "j", "type": "revolute", "parent": "ground", "child": "bar"},
               {"name": "k", "type": "fixed", "parent": "bar", "child": "tip_body")" +
                                           tip_joint + "}]}",
                                       "mesh_body_model");
}

std::string mesh_json(const std::string& mesh_extra, const std::string& body_extra = "") {
  return R"({"mesh": {"file": ")" + kData +
         R"(/slender_cps8.inp", "element_set": "BAR", "thickness": 0.002)" + mesh_extra +
         R"(}, "material": {"E": 2.1e11, "poisson": 0.3, "density": 7800}, "modes": 3)" + body_extra + "}";
}

std::string number(double x) {
  std::ostringstream out;
  out << std::setprecision(17) << x;
  return out.str();
}

const fem::ShapeSampler kNoShapes = [](const std::string&, const std::map<std::string, double>&,
                                       const std::vector<double>&, std::vector<double>&,
                                       std::vector<double>&) {};

}  // namespace

TEST_CASE("a clamped CPS8 bar from a model file has the beam's first frequencies within 2 %", "[mesh_body]") {
  const model::Model mesh_model = load_with(mesh_json(R"(, "clamped_set": "ROOT")"));
  const fem::ElasticModel mesh =
      fem::build_elastic_model(mesh_model.bodies[0], mesh_model.source_file, kNoShapes);

  const double A = kThickness * kHeight, Iz = kThickness * std::pow(kHeight, 3) / 12;
  const model::Model beam_model = load_with(R"({"length": 0.4, "elements": 40, "section": {"A": )" +
                                            number(A) + R"(, "Iz": )" + number(Iz) +
                                            R"(}, "material": {"E": 2.1e11, "poisson": 0.3, "density": 7800},
                                              "modes": 3})");
  const fem::ElasticModel beam =
      fem::build_elastic_model(beam_model.bodies[0], beam_model.source_file, kNoShapes);

  REQUIRE(mesh.reduced.omega.size() == 3);
  REQUIRE(beam.reduced.omega.size() == 3);
  // The Euler-Bernoulli first frequency, to see both are the bar's bending.
  const double first = 1.875104 * 1.875104 * std::sqrt(kE * Iz / (kRho * A)) / (kLength * kLength);
  CHECK(beam.reduced.omega(0) == Approx(first).epsilon(1e-3));
  for (int k = 0; k < 3; ++k) {
    INFO("mode " << k + 1 << ": mesh " << mesh.reduced.omega(k) << " rad/s, beam " << beam.reduced.omega(k));
    CHECK(mesh.reduced.omega(k) == Approx(beam.reduced.omega(k)).epsilon(0.02));
  }
  // Mass normalised: the reduced mass is the identity, the stiffness omega^2.
  CHECK((mesh.reduced.mass - Eigen::MatrixXd::Identity(3, 3)).norm() < 1e-9);
  CHECK(mesh.reduced.stiffness(0, 0) == Approx(mesh.reduced.omega(0) * mesh.reduced.omega(0)).epsilon(1e-6));
  // The bar's whole mass is in the invariants.
  CHECK(mesh.reduced.invariants.mass == Approx(kRho * A * kLength).epsilon(1e-12));
}

TEST_CASE("a free-free mesh body keeps its elastic modes, not the rigid motions", "[mesh_body]") {
  const model::Model m = load_with(mesh_json("", R"(, "support": "free")"));
  const fem::ElasticModel free = fem::build_elastic_model(m.bodies[0], m.source_file, kNoShapes);
  REQUIRE(free.reduced.omega.size() == 3);
  // Free-free bending: (4.730041 / 1.875104)^2 = 6.3627 times the clamped first frequency.
  const double A = kThickness * kHeight, Iz = kThickness * std::pow(kHeight, 3) / 12;
  const double free_first = 4.730041 * 4.730041 * std::sqrt(kE * Iz / (kRho * A)) / (kLength * kLength);
  CHECK(free.reduced.omega(0) == Approx(free_first).epsilon(0.02));
}

TEST_CASE("bad mesh references in a model give errors naming the place and the fix", "[mesh_body]") {
  SECTION("a clamped node set the mesh does not have") {
    const model::Model m = load_with(mesh_json(R"(, "clamped_set": "RUT")"));
    try {
      fem::build_elastic_model(m.bodies[0], m.source_file, kNoShapes);
      FAIL("no error");
    } catch (const model::ModelError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find("/bodies/0/flexible/mesh/clamped_set") != std::string::npos);
      CHECK(what.find("RUT") != std::string::npos);
      CHECK(what.find("ROOT") != std::string::npos);  // the sets it has
    }
  }
  SECTION("a mesh file that does not exist") {
    const model::Model m = load_with(R"({"mesh": {"file": "no_such.inp", "clamped_set": "ROOT"},
      "material": {"E": 1e9, "poisson": 0.3, "density": 1000}, "modes": 2})");
    CHECK_THROWS_WITH(fem::build_elastic_model(m.bodies[0], m.source_file, kNoShapes),
                      Catch::Contains("/bodies/0/flexible/mesh/file") && Catch::Contains("no_such.inp"));
  }
  SECTION("an element set the mesh does not have") {
    const model::Model m = load_with(mesh_json(R"(, "clamped_set": "ROOT")"));
    model::Body body = m.bodies[0];
    body.elastic.mesh.element_set = "BRA";
    CHECK_THROWS_WITH(fem::build_elastic_model(body, m.source_file, kNoShapes),
                      Catch::Contains("/bodies/0/flexible/mesh/element_set") && Catch::Contains("BAR"));
  }
  SECTION("the model file's own rules") {
    CHECK_THROWS_WITH(load_with(mesh_json("")), Catch::Contains("clamped_set"));
    CHECK_THROWS_WITH(load_with(R"({"mesh": {"file": "x.inp", "clamped_set": "ROOT"},
      "material": {"E": 1e9, "poisson": 0.3, "density": 1000}})"),
                      Catch::Contains("needs \"modes\""));
    CHECK_THROWS_WITH(load_with(R"({"mesh": {"file": "x.inp", "clamped_set": "ROOT"}, "length": 1,
      "material": {"E": 1e9, "poisson": 0.3, "density": 1000}, "modes": 2})"),
                      Catch::Contains("/bodies/0/flexible/length"));
    CHECK_THROWS_WITH(load_with(R"({"mesh": {"file": "x.inp", "clamped_set": "ROOT"},
      "material": {"E": 1e9, "density": 1000}, "modes": 2})"),
                      Catch::Contains("poisson"));
  }
}

TEST_CASE("a joint on a node set moves with the set's averaged motion, as the beam's tip node",
          "[mesh_body]") {
  const model::Model mesh_model =
      load_with(mesh_json(R"(, "clamped_set": "ROOT")"), R"(, "parent_node_set": "TIP")");
  REQUIRE(mesh_model.joints[1].parent_node == 0);
  const fem::ElasticModel mesh =
      fem::build_elastic_model(mesh_model.bodies[0], mesh_model.source_file, kNoShapes);
  REQUIRE(mesh.interfaces.size() == 1);
  CHECK((mesh.point_position(0) - Eigen::Vector3d(kLength, 0, 0)).norm() < 1e-12);

  const double A = kThickness * kHeight, Iz = kThickness * std::pow(kHeight, 3) / 12;
  const model::Model beam_model =
      load_with(R"({"length": 0.4, "elements": 40, "section": {"A": )" + number(A) + R"(, "Iz": )" +
                number(Iz) + R"(}, "material": {"E": 2.1e11, "density": 7800}, "modes": 3})");
  const fem::ElasticModel beam =
      fem::build_elastic_model(beam_model.bodies[0], beam_model.source_file, kNoShapes);
  const int tip = beam.body.num_nodes() - 1;
  // The first mode's tip slope over its tip deflection, L phi'(L) / phi(L) = 1.3765 for the cantilever.
  for (const fem::ElasticModel* b : {&mesh, &beam}) {
    const int node = b == &mesh ? 0 : tip;
    const double ratio = kLength * b->point_rotation(node)(2, 0) / b->point_translation(node)(1, 0);
    INFO((b == &mesh ? "mesh" : "beam") << ": L theta_z / v at the tip = " << ratio);
    CHECK(ratio == Approx(1.3765).epsilon(0.01));
  }
  CHECK(std::abs(mesh.point_translation(0)(1, 0)) ==
        Approx(std::abs(beam.point_translation(tip)(1, 0))).epsilon(0.02));
}

TEST_CASE("a joint on a node set the mesh does not have: the joint's place and the sets there are",
          "[mesh_body]") {
  const model::Model m = load_with(mesh_json(R"(, "clamped_set": "ROOT")"), R"(, "parent_node_set": "TOP")");
  CHECK_THROWS_WITH(
      fem::build_elastic_model(m.bodies[0], m.source_file, kNoShapes),
      Catch::Contains("/joints/1/parent_node_set") && Catch::Contains("TOP") && Catch::Contains("ROOT, TIP"));
  CHECK_THROWS_WITH(load_with(R"({"length": 0.4, "elements": 4, "section": {"A": 1e-4, "Iz": 1e-9},
      "material": {"E": 2.1e11, "density": 7800}})",
                              R"(, "parent_node_set": "TIP")"),
                    Catch::Contains("/joints/1/parent_node_set") && Catch::Contains("not a mesh body"));
}

TEST_CASE(
    "Craig-Bampton: the tip interface's statics are the cantilever's, the first frequency the clamped one",
    "[mesh_body]") {
  const model::Model m = load_with(mesh_json(R"(, "clamped_set": "ROOT", "reduction": "craig-bampton")"),
                                   R"(, "parent_node_set": "TIP")");
  const fem::ElasticModel cb = fem::build_elastic_model(m.bodies[0], m.source_file, kNoShapes);
  REQUIRE(cb.reduced.names.size() == 6);  // u_x, u_y, theta_z of TIP, then 3 fixed-interface modes
  // Each constraint mode moves the interface point by one rigid motion alone, scaled so that the
  // mode has unit modal mass (as the fixed-interface modes).
  const Eigen::MatrixXd t = cb.point_translation(0), r = cb.point_rotation(0);
  const Eigen::Vector3d scale(t(0, 0), t(1, 1), r(2, 2));
  CHECK(scale.minCoeff() > 0);
  CHECK(std::abs(t(0, 1)) + std::abs(t(0, 2)) + std::abs(t(1, 0)) + std::abs(t(1, 2)) <
        1e-9 * scale.maxCoeff());
  CHECK(std::abs(r(2, 0)) + std::abs(r(2, 1)) < 1e-9 * scale.maxCoeff());
  for (int j = 0; j < 3; ++j) CHECK(cb.reduced.mass(j, j) == Approx(1.0).epsilon(1e-12));
  CHECK(t.rightCols(3).norm() < 1e-9);  // fixed-interface modes hold the interface
  // Statics: the flexibility at the tip, the inverse of the constraint-mode stiffness (exact Schur
  // complement) in the interface's own motions.
  const Eigen::Matrix3d flexibility =
      scale.asDiagonal() * cb.reduced.stiffness.topLeftCorner(3, 3).inverse() * scale.asDiagonal();
  const double Iz = kThickness * std::pow(kHeight, 3) / 12, A = kThickness * kHeight;
  CHECK(flexibility(1, 1) == Approx(std::pow(kLength, 3) / (3 * kE * Iz)).epsilon(0.02));
  CHECK(flexibility(2, 2) == Approx(kLength / (kE * Iz)).epsilon(0.02));
  CHECK(flexibility(0, 0) == Approx(kLength / (kE * A)).epsilon(0.02));

  const model::Model modal_model = load_with(mesh_json(R"(, "clamped_set": "ROOT")"));
  const fem::ElasticModel modal =
      fem::build_elastic_model(modal_model.bodies[0], modal_model.source_file, kNoShapes);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(cb.reduced.stiffness, cb.reduced.mass);
  CHECK(std::sqrt(eig.eigenvalues()(0)) == Approx(modal.reduced.omega(0)).epsilon(1e-3));
  CHECK(std::sqrt(eig.eigenvalues()(1)) == Approx(modal.reduced.omega(1)).epsilon(1e-2));
}

TEST_CASE("Craig-Bampton without an interface is refused where it is asked for", "[mesh_body]") {
  CHECK_THROWS_WITH(
      load_with(mesh_json(R"(, "clamped_set": "ROOT", "reduction": "craig-bampton")")),
      Catch::Contains("/bodies/0/flexible/mesh/reduction") && Catch::Contains("parent_node_set"));
}

TEST_CASE("geometric stiffening: a slender CPS8 bar's second-order field is the beam's foreshortening",
          "[mesh_body][mesh_foreshortening]") {
  const model::Model mesh_model =
      load_with(mesh_json(R"(, "clamped_set": "ROOT")"), R"(, "parent_node_set": "TIP")");
  REQUIRE(mesh_model.bodies[0].elastic.geometric_stiffening);  // the default for a clamped mesh body
  const fem::ElasticModel mesh =
      fem::build_elastic_model(mesh_model.bodies[0], mesh_model.source_file, kNoShapes);
  const double A = kThickness * kHeight, Iz = kThickness * std::pow(kHeight, 3) / 12;
  const model::Model beam_model =
      load_with(R"({"length": 0.4, "elements": 40, "section": {"A": )" + number(A) + R"(, "Iz": )" +
                number(Iz) + R"(}, "material": {"E": 2.1e11, "density": 7800}, "modes": 3})");
  const fem::ElasticModel beam =
      fem::build_elastic_model(beam_model.bodies[0], beam_model.source_file, kNoShapes);
  REQUIRE(mesh.foreshortening);
  REQUIRE(beam.foreshortening);
  REQUIRE(mesh.second_order.cols() == 6);
  const int tip = beam.body.num_nodes() - 1;
  // H_x at the tip, sum m H_x and sum m x H_x (which carries the centrifugal
  // stiffening): mode by mode within 2 % of the beam's (the modes' signs are
  // the same canonical ones; the bar is as in the frequency test above).
  const std::pair<const char*, std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> cases[] = {
      {"tip H_x", {mesh.foreshortening->node[0][0], beam.foreshortening->node[tip][0]}},
      {"sum m H_x", {mesh.foreshortening->mass[0], beam.foreshortening->mass[0]}},
      {"sum m x H_x", {mesh.foreshortening->moment[0], beam.foreshortening->moment[0]}}};
  for (const auto& [what, pair] : cases) {
    const auto& [m, b] = pair;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        INFO(what << " (" << i << ", " << j << "): mesh " << m(i, j) << ", beam " << b(i, j));
        CHECK(std::abs(m(i, j) - b(i, j)) < 0.02 * b.cwiseAbs().maxCoeff());
      }
    INFO(what << ": mesh (1, 1) " << m(0, 0) << ", beam " << b(0, 0));
    CHECK(m(0, 0) == Approx(b(0, 0)).epsilon(0.02));
    // The transverse parts (Poisson's ratio, the section's own shortening) are small.
  }
  CHECK(mesh.foreshortening->node[0][1].cwiseAbs().maxCoeff() <
        0.05 * mesh.foreshortening->node[0][0].cwiseAbs().maxCoeff());
}

TEST_CASE("geometric stiffening of a free mesh body: off by default, refused when asked for", "[mesh_body]") {
  const model::Model free = load_with(mesh_json("", R"(, "support": "free")"));
  CHECK_FALSE(free.bodies[0].elastic.geometric_stiffening);
  CHECK_FALSE(fem::build_elastic_model(free.bodies[0], free.source_file, kNoShapes).foreshortening);
  CHECK_THROWS_WITH(load_with(mesh_json("", R"(, "support": "free", "geometric_stiffening": true)")),
                    Catch::Contains("/bodies/0/flexible/geometric_stiffening") &&
                        Catch::Contains("free mesh body") && Catch::Contains("\"clamped_set\""));
  const model::Model off =
      load_with(mesh_json(R"(, "clamped_set": "ROOT")", R"(, "geometric_stiffening": false)"));
  CHECK_FALSE(fem::build_elastic_model(off.bodies[0], off.source_file, kNoShapes).foreshortening);
}
