// SPDX-License-Identifier: GPL-2.0-or-later
// Mesh bodies whose K and M are imported from CalculiX's
// *FREQUENCY, SOLVER=MATRIXSTORAGE files (issue 38): a small C3D8 bar
// (data/matrices, tests/fem/ccx/make_matrix_reference.py), clamped from the
// job's reduced files (the held dofs left out), free and clamped from the full
// files, against kanegen's own assembly of the same mesh and against
// CalculiX's *FREQUENCY on it; and the errors of bad files.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fem/ccx_matrices.hpp"
#include "fem/elastic_model.hpp"
#include "model/model_error.hpp"
#include "model_text.hpp"

namespace {

using namespace kanegen;

const std::string kDir = std::string(KANEGEN_FEM_DATA_DIR) + "/matrices/";

const fem::ShapeSampler kNoShapes = [](const std::string&, const std::map<std::string, double>&,
                                       const std::vector<double>&, std::vector<double>&,
                                       std::vector<double>&) {};

/// `matrices`: the "matrices" value (empty: none); `support`: "clamped" or "free".
std::string body_json(const std::string& matrices, const std::string& support, const std::string& extra = "",
                      double density = 7850) {
  std::ostringstream density_text;
  density_text.precision(17);
  density_text << density;
  const std::string clamp = support == "clamped" ? R"(, "clamped_set": "ROOT")" : "";
  return R"({"mesh": {"file": ")" + kDir + R"(bar_c3d8_small.inp")" + clamp +
         (matrices.empty() ? "" : R"(, "matrices": )" + matrices) +
         R"(}, "material": {"E": 2.1e11, "poisson": 0.3, "density": )" + density_text.str() +
         R"(}, "support": ")" + support + R"(", "modes": 12, "geometric_stiffening": false)" + extra + "}";
}

std::string files(const std::string& job) {
  return R"({"stiffness": ")" + kDir + job + R"(.sti", "mass": ")" + kDir + job + R"(.mas", "dofs": ")" +
         kDir + job + R"(.dof"})";
}

model::Model load_body(const std::string& flexible) {
  return kanegen_test::load_model_text(
      R"({"format": "kanegen-model", "version": 1, "name": "bar", "bodies": [{"name": "bar", "flexible": )" +
          flexible +
          R"(}], "joints": [{"name": "j", "type": "revolute", "parent": "ground", "child": "bar"}]})",
      "ccx_matrices");
}

Eigen::VectorXd omega(const std::string& flexible) {
  const model::Model m = load_body(flexible);
  return fem::build_elastic_model(m.bodies[0], m.source_file, kNoShapes).reduced.omega;
}

/// The error of building the body `flexible` (load or reduction), or "".
std::string error_of(const std::string& flexible) {
  try {
    omega(flexible);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

/// CalculiX's omega (rad/s) of `support`, modes in file order.
std::vector<double> ccx_omega(const std::string& support) {
  std::ifstream in(kDir + "bar_c3d8_small_ccx.txt");
  std::vector<double> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    std::string s;
    int mode = 0;
    double rad = 0, hz = 0;
    row >> s >> mode >> rad >> hz;
    if (s == support) out.push_back(rad);
  }
  return out;
}

void check_same(const Eigen::VectorXd& imported, const Eigen::VectorXd& own, const std::vector<double>& ccx) {
  REQUIRE(imported.size() == 12);
  REQUIRE(own.size() == 12);
  REQUIRE(ccx.size() == 12);
  for (int k = 0; k < 12; ++k) {
    INFO("mode " << k + 1 << ": imported " << imported(k) << ", own " << own(k) << ", ccx " << ccx[k]);
    CHECK(std::abs(imported(k) - own(k)) <= 1e-6 * own(k));
    CHECK(std::abs(imported(k) - ccx[k]) <= 1e-6 * ccx[k]);
  }
}

/// A file of `text` in the temporary directory, removed with the object.
struct TempFile {
  std::string path;
  TempFile(const std::string& name, const std::string& text)
      : path((std::filesystem::temp_directory_path() /
              ("kanegen_ccx_" + std::to_string(::getpid()) + "_" + name))
                 .string()) {
    std::ofstream(path) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The error of read_ccx_matrix on `text` with n rows, or "".
std::string matrix_error(const std::string& text, int n) {
  const TempFile f("m.sti", text);
  try {
    fem::read_ccx_matrix(f.path, n);
  } catch (const model::ModelError& e) {
    return e.what();
  }
  return "";
}

std::string dofs_error(const std::string& text) {
  const TempFile f("m.dof", text);
  try {
    fem::read_ccx_dofs(f.path);
  } catch (const model::ModelError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("imported CalculiX matrices give the mesh's own frequencies and CalculiX's, to 1e-6",
          "[ccx_matrices]") {
  SECTION("clamped, from the job's files without the held dofs") {
    check_same(omega(body_json(files("clamped"), "clamped")), omega(body_json("", "clamped")),
               ccx_omega("clamped"));
  }
  SECTION("clamped by kanegen, from the full files") {
    check_same(omega(body_json(files("free"), "clamped")), omega(body_json("", "clamped")),
               ccx_omega("clamped"));
  }
  SECTION("free: the first 12 elastic modes") {
    check_same(omega(body_json(files("free"), "free")), omega(body_json("", "free")), ccx_omega("free"));
  }
}

TEST_CASE("a body with imported matrices refuses geometric stiffening", "[ccx_matrices]") {
  std::string text = body_json(files("clamped"), "clamped");
  text.replace(text.find(R"("geometric_stiffening": false)"), 29, R"("geometric_stiffening": true)");
  const std::string e = error_of(text);
  CHECK_THAT(e, Catch::Contains("/geometric_stiffening"));
  CHECK_THAT(e, Catch::Contains("no element stresses"));
  CHECK_THAT(e, Catch::Contains("remove \"matrices\""));
}

TEST_CASE("bad CalculiX matrix files are refused naming the file, the line and the fix", "[ccx_matrices]") {
  CHECK_THAT(matrix_error("1 1 2.0\n1 2 x\n", 2),
             Catch::Contains("m.sti: line 2: not an entry 'row column value'"));
  CHECK_THAT(matrix_error("1 1 2.0\n1 2 nan\n", 2), Catch::Contains("line 2: not an entry"));
  CHECK_THAT(matrix_error("1 1 2.0\n1 2 1e999\n", 2), Catch::Contains("line 2: not an entry"));
  CHECK_THAT(matrix_error("1 1 2.0 4\n", 2), Catch::Contains("line 1: not an entry"));
  CHECK_THAT(matrix_error("1 1 2.0\n1 3 1.0\n", 2),
             Catch::Contains("line 2: the row or column is not in 1..2") &&
                 Catch::Contains(".dof file of the same"));
  CHECK_THAT(matrix_error("0 1 2.0\n", 2), Catch::Contains("line 1: the row or column"));
  CHECK_THAT(matrix_error("-1 1 2.0\n", 2), Catch::Contains("line 1: the row or column"));
  CHECK_THAT(matrix_error("99999999999 1 2.0\n", 2), Catch::Contains("line 1: the row or column"));
  CHECK_THAT(matrix_error("1 2 1.0\n2 1 1.5\n", 2),
             Catch::Contains("line 2: the matrix is not symmetric") && Catch::Contains("line 1"));
  CHECK_THAT(matrix_error("1 2 1.0\n1 2 1.0\n", 2), Catch::Contains("line 2: entry (1, 2) is given twice"));
  CHECK_THAT(matrix_error("", 2), Catch::Contains("m.sti: file: the matrix file is empty"));
  CHECK_THAT(matrix_error(std::string(300, '1') + "\n", 2), Catch::Contains("line 1: the line is longer"));
  // Both triangles agreeing, and a lower-triangle entry alone, are accepted.
  CHECK(matrix_error("1 1 2.0\n1 2 1.0\n2 1 1.0\n2 2 3.0\n\n", 2).empty());
  const TempFile lower("l.mas", "2 1 1.5\n1 1 2\n2 2 3\n");
  const Eigen::MatrixXd a = Eigen::MatrixXd(fem::read_ccx_matrix(lower.path, 2));
  CHECK(a(0, 1) == 1.5);
  CHECK(a(1, 0) == 1.5);
  CHECK(a(1, 1) == 3.0);
  // A file cut short lacks the last diagonal entries; a diagonal is positive.
  CHECK_THAT(matrix_error("1 1 2.0\n1 2 1.0\n", 2),
             Catch::Contains("m.sti: line 2: the file ends without the diagonal entry (2, 2)") &&
                 Catch::Contains("cut short") && Catch::Contains("complete file"));
  CHECK_THAT(matrix_error("1 1 2.0\n1 2 1.0\n2 2 0\n", 2),
             Catch::Contains("line 3: the diagonal entry (2, 2) is not positive"));
  CHECK_THAT(matrix_error("1 1 2.0\n2 2 3.0e+\n", 2), Catch::Contains("line 2: not an entry"));

  CHECK_THAT(dofs_error("1.1\n1.2\nx\n"), Catch::Contains("m.dof: line 3: not a dof node.direction"));
  CHECK_THAT(dofs_error("1.1\n\n1.2\n"), Catch::Contains("line 2: not a dof"));
  CHECK_THAT(dofs_error("1.1\n1.4\n"), Catch::Contains("line 2: direction 4 of node 1 is not a translation"));
  CHECK_THAT(dofs_error("1.1\n1.1\n"), Catch::Contains("line 2: node 1 direction 1 is listed twice"));
  CHECK_THAT(dofs_error("1.-1\n"), Catch::Contains("line 1: not a dof"));
  CHECK_THAT(dofs_error(""), Catch::Contains("the dof map is empty"));
}

TEST_CASE("matrices that do not fit the mesh or the model are refused", "[ccx_matrices]") {
  const std::string sti = kDir + "clamped.sti", mas = kDir + "clamped.mas", dof = kDir + "clamped.dof";
  const auto with = [](const std::string& k, const std::string& m, const std::string& d) {
    return R"({"stiffness": ")" + k + R"(", "mass": ")" + m + R"(", "dofs": ")" + d + R"("})";
  };
  SECTION("a missing file") {
    const std::string e = error_of(body_json(with(sti, kDir + "none.mas", dof), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/mass") &&
                      Catch::Contains("none.mas: file: cannot open the matrix"));
  }
  SECTION("a node that is not the mesh's") {
    std::string text = read_all(dof);
    text.replace(0, text.find('.'), "999");
    const TempFile bad("bad.dof", text);
    const std::string e = error_of(body_json(with(sti, mas, bad.path), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/dofs") &&
                      Catch::Contains("bad.dof: line 1: node 999 is on none") &&
                      Catch::Contains("same mesh"));
  }
  SECTION("the held dofs missing from a free body's matrices") {
    const std::string e = error_of(body_json(with(sti, mas, dof), "free"));
    CHECK_THAT(e, Catch::Contains("clamped.dof lists no row for node 1 direction 1") &&
                      Catch::Contains("*BOUNDARY"));
  }
  SECTION("fewer rows in the dof map than the matrices have") {
    std::string text = read_all(dof);
    text.erase(text.rfind('\n', text.size() - 2) + 1);
    const TempFile bad("short.dof", text);
    const std::string e = error_of(body_json(with(sti, mas, bad.path), "clamped"));
    CHECK_THAT(e, Catch::Contains("lists no row for node") || Catch::Contains("is not in 1.."));
  }
  SECTION("the z rows CalculiX writes for a plane mesh") {
    const TempFile plane("plane.dof", "1.1\n1.2\n1.3\n");
    std::string text = body_json(with(sti, mas, plane.path), "clamped");
    text.replace(text.find("bar_c3d8_small.inp"), 18, "../plate_cps4.inp");
    text.replace(text.find(R"("mesh": {)"), 9, R"("mesh": {"thickness": 0.002, )");
    const std::string e = error_of(text);
    CHECK_THAT(e,
               Catch::Contains("/mesh/matrices/dofs") &&
                   Catch::Contains("plane.dof: line 3: direction 3 of node 1: the body's plane elements") &&
                   Catch::Contains("import the matrices of a solid mesh"));
  }
  SECTION("a dof map of more rows than the matrices") {
    const TempFile bad("long.dof", read_all(dof) + "1.1\n");
    const std::string e = error_of(body_json(with(sti, mas, bad.path), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/stiffness") && Catch::Contains("clamped.sti: line 2070") &&
                      Catch::Contains("without the diagonal entry (109, 109) of the 109 dofs"));
  }
  SECTION("a stiffness file cut short") {
    std::string text = read_all(sti);
    for (int k = 0; k < 3; ++k) text.erase(text.rfind('\n', text.size() - 2) + 1);
    const TempFile bad("cut.sti", text);
    const std::string e = error_of(body_json(with(bad.path, mas, dof), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/stiffness") && Catch::Contains("cut.sti: line 2067") &&
                      Catch::Contains("without the diagonal entry (108, 108)"));
  }
  SECTION("a stiffness file cut within its last number") {
    // "1.2637891737772e+09\n" cut to "1.2637891737772e+": not a number.
    std::string text = read_all(sti);
    text.erase(text.size() - 3);
    const TempFile bad("cut.sti", text);
    CHECK_THAT(error_of(body_json(with(bad.path, mas, dof), "clamped")),
               Catch::Contains("cut.sti: line 2070: not an entry"));
    // Cut to "1.263789173777": a number, but not the stiffness.
    text = read_all(sti);
    text.erase(text.size() - 6);
    const TempFile changed("changed.sti", text);
    CHECK_THAT(
        error_of(body_json(with(changed.path, mas, dof), "clamped")),
        Catch::Contains("changed.sti strains the body's rigid translation along z at node 42 direction 3"));
  }
  SECTION("a line missing within the stiffness file") {
    std::string text = read_all(sti);
    const std::size_t line_1001 = [&] {
      std::size_t at = 0;
      for (int k = 0; k < 1000; ++k) at = text.find('\n', at) + 1;
      return at;
    }();
    // An off-diagonal entry that is not zero.
    std::size_t at = line_1001;
    for (;;) {
      const std::size_t end = text.find('\n', at);
      std::istringstream row(text.substr(at, end - at));
      int i = 0, j = 0;
      double v = 0;
      row >> i >> j >> v;
      if (i != j && std::abs(v) > 1e6) break;
      at = end + 1;
    }
    text.erase(at, text.find('\n', at) - at + 1);
    const TempFile bad("gap.sti", text);
    const std::string e = error_of(body_json(with(bad.path, mas, dof), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/stiffness") &&
                      Catch::Contains("gap.sti strains the body's rigid") &&
                      Catch::Contains("a line missing or changed"));
  }
  SECTION("a NaN in the mass file") {
    std::string text = read_all(mas);
    const std::size_t line_2 = text.find('\n') + 1;
    text.replace(line_2, text.find('\n', line_2) - line_2, "1 2 nan");
    const TempFile bad("nan.mas", text);
    const std::string e = error_of(body_json(with(sti, bad.path, dof), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/mass") &&
                      Catch::Contains("nan.mas: line 2: not an entry") && Catch::Contains("unchanged"));
  }
  SECTION("another density than the job's") {
    const std::string e = error_of(body_json(with(sti, mas, dof), "clamped", "", 7800));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/mass") &&
                      Catch::Contains("is not the consistent mass of the mesh with density 7800") &&
                      Catch::Contains("*DENSITY"));
  }
  SECTION("an asymmetric stiffness") {
    std::string text = read_all(sti) + "2 1 123.0\n";
    const TempFile bad("asym.sti", text);
    const std::string e = error_of(body_json(with(bad.path, mas, dof), "clamped"));
    CHECK_THAT(e, Catch::Contains("/mesh/matrices/stiffness") && Catch::Contains("asym.sti: line") &&
                      Catch::Contains("not symmetric"));
  }
}
