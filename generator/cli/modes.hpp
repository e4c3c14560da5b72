// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen modes: natural frequencies and mode shapes of a model linearised
// about its initial state (t = 0), from the compiled kernels (docs/modes.md).
// The eigen-coordinates are the elastic coordinates (and, on request or in a
// model without flexible bodies, the free joint coordinates); the other
// joints are held at their initial state, prescribed joints move as
// prescribed.
#pragma once

#include <string>
#include <vector>

#include "runner/runner_build.hpp"

namespace kanegen::cli {

struct ModesOptions {
  std::string model;
  std::vector<std::string> sets;  ///< NAME=VALUE parameter values
  std::vector<std::string> q0;    ///< NAME=VALUE initial coordinates (the operating point)
  std::vector<std::string> u0;    ///< NAME=VALUE initial speeds
  bool free_joints = false;       ///< the free joint coordinates join the eigenproblem
  int count = 0;                  ///< print the first `count` modes (0: all)
  bool matrices = false;          ///< also print M, K, C and r
  double step = 1e-6;             ///< relative finite-difference step
  runner::BuildOptions build;
};

/// Prints the modes as JSON on stdout. Returns 0, or 1 if the linearised
/// model is unstable (the JSON is printed too, the unstable modes marked,
/// and the reason goes to stderr). Throws model::ModelError for a bad model,
/// std::runtime_error for a bad option, a singular mass matrix or a runner
/// that fails.
int modes(const ModesOptions& options);

}  // namespace kanegen::cli
