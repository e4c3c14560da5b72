// SPDX-License-Identifier: GPL-2.0-or-later
// `kanegen animate`: a result CSV of `kanegen simulate` and its model turned
// into a ParaView time series or one page for the browser (docs/animation.md).
// The bodies are placed by the numeric path's world poses (numeric/poses.hpp),
// not by the generated kernels, so the picture is also a second opinion on
// the run's outputs.
#pragma once

#include <string>
#include <vector>

#include "model/load.hpp"

namespace kanegen::animate {

struct AnimateOptions {
  std::string result;             ///< CSV written by kanegen simulate
  std::string model;              ///< the model the run was of
  std::string output_dir;         ///< where <model>.pvd and <model>_NNNNN.vtu go, or <model>.html
  std::string format = "vtk";     ///< vtk: a ParaView series; html: one page with a three.js viewer
  double scale = 1.0;             ///< magnification of elastic displacements drawn
  std::size_t frames = 200;       ///< at most this many frames, spread over the run
  std::vector<std::string> sets;  ///< NAME=VALUE: parameter values of the run
  model::LoadOptions load;
  bool verbose = true;  ///< progress on stderr
};

/// The columns a result CSV of the model starts with after t (its state, as
/// kanegen simulate writes it; parameters at their defaults).
std::vector<std::string> result_state_columns(const std::string& model_file,
                                              const model::LoadOptions& load = {});

/// Writes the series, or the page; returns the path of the .pvd or .html.
/// Throws model::ModelError for the model, std::runtime_error naming the
/// file and the fix for a CSV that is not of this model, an unknown --set
/// name, an unwritable directory or (html) three.js not found. Each file is
/// written whole or not at all; the .pvd last.
std::string animate(const AnimateOptions& options);

}  // namespace kanegen::animate
