// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen animate on a shipped model (one ctest per file of models/, the
// file in $KANEGEN_ANIMATE_MODEL): a three-row result of the model's own
// state columns drawn in both formats, a ParaView series of three frames and
// one page. The positions drawn are checked against the runs' outputs by
// check_vtk.py and check_html.py; this test covers the rest of the shipped
// models, whose bodies, joints and meshes must all be drawable.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "animate/animate.hpp"
#include "animate/three_js.hpp"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// t = 0, 0.5, 1 with the coordinates moved a little (a quaternion's w stays
/// near 1) and the speeds 0.
void write_result(const fs::path& csv, const std::vector<std::string>& state) {
  std::ofstream out(csv);
  out << "t";
  for (const std::string& c : state) out << "," << c;
  out << "\n";
  const auto ends = [](const std::string& s, const char* tail) {
    const std::string t(tail);
    return s.size() > t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
  };
  for (int row = 0; row < 3; ++row) {
    out << 0.5 * row;
    for (std::size_t i = 0; i < state.size(); ++i) {
      const std::string& c = state[i];
      const bool speed = ends(c, "_dot") || ends(c, "_wx") || ends(c, "_wy") || ends(c, "_wz");
      out << "," << (ends(c, "_qw") ? 1.0 : speed ? 0.0 : 0.01 * row * static_cast<double>(1 + i % 3));
    }
    out << "\n";
  }
}

}  // namespace

TEST_CASE("both formats of one shipped model ($KANEGEN_ANIMATE_MODEL)", "[animate][every_model]") {
  const char* model = std::getenv("KANEGEN_ANIMATE_MODEL");
  if (!model) {
    WARN("KANEGEN_ANIMATE_MODEL is not set: ctest sets it, one test per shipped model");
    return;
  }
  const std::string stem = fs::path(model).stem().string();
  const fs::path dir = fs::temp_directory_path() / ("kanegen_animate_every_" + stem);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> state = kanegen::animate::result_state_columns(model);
  REQUIRE_FALSE(state.empty());
  const fs::path csv = dir / "run.csv";
  write_result(csv, state);

  kanegen::animate::AnimateOptions vtk;
  vtk.result = csv.string();
  vtk.model = model;
  vtk.output_dir = (dir / "vtk").string();
  vtk.scale = 10;
  vtk.verbose = false;
  const fs::path pvd = kanegen::animate::animate(vtk);
  REQUIRE(fs::exists(pvd));
  const std::string series = slurp(pvd);
  int frames = 0;
  for (const auto& entry : fs::directory_iterator(dir / "vtk"))
    if (entry.path().extension() == ".vtu") {
      ++frames;
      CHECK(series.find(entry.path().filename().string()) != std::string::npos);
      CHECK(slurp(entry.path()).find("<UnstructuredGrid>") != std::string::npos);
    }
  CHECK(frames == 3);

  kanegen::animate::AnimateOptions html = vtk;
  html.format = "html";
  html.output_dir = (dir / "html").string();
  try {
    kanegen::animate::three_js_text();
  } catch (const std::runtime_error& e) {
    if (std::getenv("KANEGEN_REQUIRE_BROWSER")) FAIL(e.what());
    WARN("no html page: " << e.what());
    fs::remove_all(dir);
    return;
  }
  const fs::path page = kanegen::animate::animate(html);
  const std::string text = slurp(page);
  CHECK(text.size() > 100000);  // three.js is inlined
  CHECK(text.find("</html>") != std::string::npos);
  fs::remove_all(dir);
}
