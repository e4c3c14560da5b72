// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/animate.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "animate/html_page.hpp"
#include "animate/result_table.hpp"
#include "animate/scene.hpp"
#include "animate/shapes.hpp"
#include "animate/three_js.hpp"
#include "animate/viewer_data.hpp"
#include "animate/vtk_writer.hpp"
#include "kanegen/runtime/text.hpp"
#include "model/expression_eval.hpp"
#include "model/model_check.hpp"
#include "model/model_error.hpp"
#include "model/names.hpp"
#include "numeric/instance.hpp"
#include "numeric/spherical.hpp"

namespace kanegen::animate {
namespace {

namespace fs = std::filesystem;

/// Writes `text` to `path` through a temporary file in the same directory,
/// so that `path` is the old file or the new one, never a part.
void write_whole(const fs::path& path, const std::string& text) {
  const fs::path part = path.string() + ".part";
  {
    std::ofstream out(part, std::ios::binary);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(part, ignored);
      throw std::runtime_error(path.string() + ": cannot be written; check the disk space and permissions");
    }
  }
  fs::rename(part, path);
}

model::ParameterValues parameter_values(const model::Model& m, const std::vector<std::string>& sets) {
  model::ParameterValues values = model::default_parameter_values(m);
  for (const std::string& set : sets) {
    const auto eq = set.find('=');
    double value = 0;
    if (eq == std::string::npos || !runtime::parse_number(std::string_view(set).substr(eq + 1), &value))
      throw std::runtime_error("--set " + set + ": give NAME=VALUE with a finite number");
    const std::string name = set.substr(0, eq);
    if (!values.count(name)) {
      std::vector<std::string> names;
      for (const auto& [known, v] : values) names.push_back(known);
      const std::string guess = model::nearest(name, names);
      throw std::runtime_error("--set " + set + ": " + m.name + " has no parameter '" + name + "'; " +
                               (!guess.empty()  ? "did you mean '" + guess + "'?"
                                : names.empty() ? std::string("it has none")
                                                : "its parameters are " + model::join(names)));
    }
    values[name] = value;
  }
  model::check_parameter_values(m, values, "--set");
  return values;
}

/// The columns a run of the model starts with after t: its coordinates (a
/// spherical joint's quaternion x, y, z, and every w after the others), then
/// its speeds (<coordinate>_dot, a spherical joint's <joint>_wx, _wy, _wz).
std::vector<std::string> state_columns(const numeric::Instance& instance) {
  std::vector<std::string> names = numeric::kernel_coordinate_names(instance), speeds;
  for (int r = 0; r < instance.coordinates(); ++r) {
    const numeric::JointData* j =
        r < instance.joint_coordinates() ? &instance.joints[instance.coordinate_joint[r]] : nullptr;
    if (j && j->motion == numeric::Motion::ball)
      speeds.push_back(j->name + "_w" + "xyz"[r - j->coordinate]);
    else
      speeds.push_back(instance.coordinate_names[r] + "_dot");
  }
  names.insert(names.end(), speeds.begin(), speeds.end());
  return names;
}

/// Per coordinate of the model's kernels (numeric/spherical.hpp), its column
/// in the table: simulate writes t, then the state (state_columns), then
/// outputs, so a CSV of another model is told by the columns of its state.
std::vector<int> coordinate_columns(const ResultTable& table, const numeric::Instance& instance,
                                    const std::string& model_path) {
  const std::vector<std::string> state = state_columns(instance);
  const std::size_t nq = state.size() - static_cast<std::size_t>(instance.coordinates());
  for (std::size_t k = 1; k <= state.size(); ++k) {
    const bool speed = k > nq;
    const std::string& expected = state[k - 1];
    if (k >= table.columns.size() || table.columns[k] != expected)
      throw std::runtime_error(
          table.file + ": column " + std::to_string(k + 1) + " is '" +
          model::ModelError::printable(k < table.columns.size() ? table.columns[k] : "") +
          "', where a run of " + model_path + " has its " + (speed ? "speed" : "coordinate") + " '" +
          model::ModelError::printable(expected) +
          "'; give the CSV of a run of this model (kanegen simulate writes t, then every coordinate and "
          "every "
          "speed in order)");
  }
  std::vector<int> columns;
  for (std::size_t i = 0; i < nq; ++i) columns.push_back(static_cast<int>(i + 1));
  return columns;
}

/// The VTK series: a .vtu per frame, then the .pvd that lists them.
std::string write_vtk(const AnimateOptions& o, const std::string& name, const numeric::Instance& instance,
                      const ResultTable& table, const std::vector<int>& columns, const fs::path& dir) {
  const SceneBuilder builder(instance, o.scale, body_shapes(instance, o.model));
  const std::vector<std::size_t> rows = chosen_rows(table.rows.size(), o.frames);
  std::vector<std::pair<double, std::string>> frames;
  std::vector<double> q(columns.size());
  for (std::size_t f = 0; f < rows.size(); ++f) {
    const std::vector<double>& row = table.rows[rows[f]];
    for (std::size_t i = 0; i < columns.size(); ++i) q[i] = row[static_cast<std::size_t>(columns[i])];
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, "_%05zu.vtu", f);
    frames.emplace_back(row[0], name + suffix);
    write_whole(dir / frames.back().second, vtu_text(builder.at(q)));
    if (o.verbose && (f + 1 == rows.size() || (f + 1) % std::max<std::size_t>(rows.size() / 10, 1) == 0))
      std::fprintf(stderr, "kanegen: animate: %zu of %zu frames\n", f + 1, rows.size());
  }
  const fs::path pvd = dir / (name + ".pvd");
  write_whole(pvd, pvd_text(frames));
  return pvd.string();
}

/// The browser viewer: one HTML file with three.js and the frames in it.
std::string write_html(const AnimateOptions& o, const std::string& three, const std::string& name,
                       const numeric::Instance& instance, const ResultTable& table,
                       const std::vector<int>& columns, const fs::path& dir) {
  ViewerRun run{name,
                &instance,
                &table,
                chosen_rows(table.rows.size(), o.frames),
                columns,
                o.scale,
                body_shapes(instance, o.model)};
  if (o.verbose) std::fprintf(stderr, "kanegen: animate: %zu frames into one page\n", run.rows.size());
  const fs::path html = dir / (name + ".html");
  write_whole(html, viewer_page(three, viewer_json(run)));
  return html.string();
}

}  // namespace

std::vector<std::string> result_state_columns(const std::string& model_file, const model::LoadOptions& load) {
  const model::Model m = model::load_model(model_file, load);
  return state_columns(numeric::instantiate(m, parameter_values(m, {})));
}

std::string animate(const AnimateOptions& o) {
  if (!(o.scale >= 0) || !std::isfinite(o.scale))
    throw std::runtime_error("--scale " + runtime::format_double(o.scale) + ": give a finite number >= 0");
  if (o.format != "vtk" && o.format != "html")
    throw std::runtime_error("--format " + o.format + ": give vtk or html");
  // Before anything is read or written, so that a missing three.js is what is told.
  const std::string three = o.format == "html" ? three_js_text() : std::string();
  const model::Model m = model::load_model(o.model, o.load);
  const numeric::Instance instance = numeric::instantiate(m, parameter_values(m, o.sets));
  const ResultTable table = read_result_table(o.result);
  const std::vector<int> columns = coordinate_columns(table, instance, o.model);
  const fs::path dir(o.output_dir);
  std::error_code error;
  fs::create_directories(dir, error);
  if (!fs::is_directory(dir))
    throw std::runtime_error(o.output_dir + ": cannot be made a directory; give another -o");
  if (o.format == "html") return write_html(o, three, m.name, instance, table, columns, dir);
  return write_vtk(o, m.name, instance, table, columns, dir);
}

}  // namespace kanegen::animate
