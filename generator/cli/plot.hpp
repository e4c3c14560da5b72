// SPDX-License-Identifier: GPL-2.0-or-later
// `kanegen plot`: columns of a result CSV against t, drawn by gnuplot into a
// PNG, so that a run can be looked at without a plotting setup of one's own.
#pragma once

#include <string>
#include <vector>

namespace kanegen::cli {

struct PlotOptions {
  std::string csv;                   ///< a CSV written by simulate (first column t)
  std::vector<std::string> columns;  ///< the columns to draw; empty: all but t (at most kDefaultColumns)
  std::string output;                ///< the PNG; empty: the CSV's name with .png
  int width = 1000, height = 600;    ///< pixels
  std::string title;                 ///< empty: the CSV's file name
  bool verbose = true;
};

/// The gnuplot that plot() runs; throws std::runtime_error, saying how to
/// install it, if there is none (simulate --plot asks before simulating).
std::string gnuplot_or_throw();

/// The PNG the plot is written to: options.output, or the CSV's name with .png.
std::string plot_output(const PlotOptions& options);

/// Draws the plot; returns 0. Throws kanegen::runtime::UsageError for an
/// unknown column, std::runtime_error if the CSV cannot be read, gnuplot is
/// missing or fails (the PNG is then left as it was).
int plot(const PlotOptions& options);

}  // namespace kanegen::cli
