// SPDX-License-Identifier: GPL-2.0-or-later
#include "cli/plot.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cli/preflight.hpp"
#include "kanegen/runtime/options.hpp"
#include "model/model_error.hpp"
#include "model/names.hpp"
#include "runner/runner_build.hpp"

namespace kanegen::cli {
namespace fs = std::filesystem;
namespace {

/// More lines than this are unreadable in one plot: the default takes the first ones.
constexpr std::size_t kDefaultColumns = 12;

std::vector<std::string> csv_header(const std::string& csv) {
  std::ifstream in(csv);
  std::string line;
  if (!in || !std::getline(in, line))
    throw std::runtime_error(csv +
                             ": cannot read it (or it is empty); give a CSV written by kanegen simulate");
  std::vector<std::string> header;
  std::istringstream cells(line);
  for (std::string cell; std::getline(cells, cell, ',');) header.push_back(cell);
  if (header.size() < 2 || header[0] != "t")
    throw std::runtime_error(csv +
                             ": the first line is not a header starting with t; give a CSV written by "
                             "kanegen simulate");
  std::string row;
  if (!std::getline(in, row))
    throw std::runtime_error(csv + ": has no rows to plot (the run wrote only the header)");
  return header;
}

/// gnuplot's single-quoted string: a quote is written twice. A line break
/// would end the command and start another (gnuplot runs shell commands), so
/// text with control characters (a column name or path from elsewhere) is refused.
std::string quoted(const std::string& text) {
  for (const char c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw std::runtime_error(model::ModelError::printable(text) +
                               ": holds a control character, which cannot be passed to gnuplot; rename it");
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

/// gnuplot from $KANEGEN_GNUPLOT or the PATH, or "" if there is none.
std::string find_gnuplot() {
  if (const char* own = std::getenv("KANEGEN_GNUPLOT"); own && *own) return own;
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && access((fs::path(dir) / "gnuplot").c_str(), X_OK) == 0)
      return (fs::path(dir) / "gnuplot").string();
  return "";
}

}  // namespace

std::string gnuplot_or_throw() {
  const std::string gnuplot = find_gnuplot();
  if (gnuplot.empty())
    throw std::runtime_error(
        "gnuplot not found on the PATH; install it (Debian: apt-get install gnuplot-nox) or "
        "set KANEGEN_GNUPLOT to its path");
  return gnuplot;
}

namespace {

std::vector<std::size_t> chosen_columns(const PlotOptions& o, const std::vector<std::string>& header) {
  std::vector<std::size_t> chosen;
  if (o.columns.empty()) {
    for (std::size_t k = 1; k < header.size() && chosen.size() < kDefaultColumns; ++k) chosen.push_back(k);
    if (o.verbose && header.size() - 1 > kDefaultColumns)
      std::fprintf(stderr, "kanegen: plotting the first %zu of %zu columns; choose others with --y\n",
                   kDefaultColumns, header.size() - 1);
    return chosen;
  }
  const std::vector<std::string> names(header.begin() + 1, header.end());
  for (const std::string& name : o.columns) {
    std::size_t k = 1;
    while (k < header.size() && header[k] != name) ++k;
    if (k == header.size()) {
      const std::string guess = model::nearest(name, names);
      throw runtime::UsageError(
          "no column '" + name + "' in " + o.csv + "; " +
          (guess.empty() ? "columns: " + model::join(names, ", ") : "did you mean '" + guess + "'?"));
    }
    chosen.push_back(k);
  }
  return chosen;
}

std::string gnuplot_script(const PlotOptions& o, const std::vector<std::string>& header,
                           const std::vector<std::size_t>& columns, const std::string& png) {
  std::ostringstream s;
  s << "set terminal pngcairo size " << o.width << "," << o.height << " noenhanced\n"
    << "set output " << quoted(png) << "\n"
    << "set datafile separator ','\n"
    << "set xlabel 't [s]'\n"
    << "set grid\n"
    << "set key outside right top\n"
    << "set title " << quoted(o.title.empty() ? fs::path(o.csv).filename().string() : o.title) << "\n"
    << "plot ";
  for (std::size_t k = 0; k < columns.size(); ++k)
    s << (k ? ", " : "") << quoted(o.csv) << " using 1:" << columns[k] + 1 << " every ::1 with lines title "
      << quoted(header[columns[k]]);
  s << "\n";
  return s.str();
}

}  // namespace

std::string plot_output(const PlotOptions& o) {
  return o.output.empty() ? fs::path(o.csv).replace_extension(".png").string() : o.output;
}

int plot(const PlotOptions& o) {
  const std::vector<std::string> header = csv_header(o.csv);
  const std::vector<std::size_t> columns = chosen_columns(o, header);
  const std::string png = plot_output(o);
  check_output_file(png);
  const std::string gnuplot = gnuplot_or_throw();
  create_output_directory(png);
  // Through a temporary name in the same directory: a failed or stopped plot
  // leaves no half-written PNG.
  const fs::path target(png);
  const fs::path temporary = (target.has_parent_path() ? target.parent_path() : fs::path(".")) /
                             ("." + target.filename().string() + ".tmp." + std::to_string(getpid()));
  const fs::path script = temporary.string() + ".gp";
  std::ofstream(script) << gnuplot_script(o, header, columns, temporary.string());
  const int status = runner::run_program(gnuplot, {script.string()});
  std::error_code ignored;
  fs::remove(script, ignored);
  if (status != 0 || !fs::exists(temporary) || fs::file_size(temporary, ignored) == 0) {
    fs::remove(temporary, ignored);
    throw std::runtime_error(png + ": gnuplot failed (exit status " + std::to_string(status) +
                             ", its messages are above); the plot was not written");
  }
  fs::rename(temporary, target);
  if (o.verbose)
    std::fprintf(stderr, "kanegen: wrote %s (%zu columns against t)\n", png.c_str(), columns.size());
  return 0;
}

}  // namespace kanegen::cli
