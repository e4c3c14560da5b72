// SPDX-License-Identifier: GPL-2.0-or-later
// kanegen verify: the compiled generated kernels against the independent
// numeric derivation (generator/numeric) at random states and parameters,
// plus the checks that need no reference (M symmetric positive definite, M
// the Hessian of T in u, the power balance along integrated trajectories).
// See docs/verify.md.
#pragma once

#include <string>

#include "runner/runner_build.hpp"

namespace kanegen::verify {

struct VerifyOptions {
  std::string model;        ///< model file (the numeric path reads it)
  std::string kernels_dir;  ///< verify these generated files instead of generating afresh
  int samples = 100;
  unsigned long seed = 1;
  double rtol = 1e-9;          ///< tolerance of the error measures (power balance: 100 rtol)
  double spread = 0.2;         ///< parameters drawn in default * [1 - spread, 1 + spread]
  int trajectories = 3;        ///< power-balance trajectories
  double duration = 0.2;       ///< of each trajectory, s
  bool json = false;           ///< report as JSON on stdout
  runner::BuildOptions build;  ///< build.verbose: progress lines on stderr
};

/// Runs the verification and prints the report. Returns 0 if everything
/// agrees, 1 on a mismatch (each named on stderr with its state). Throws
/// model::ModelError for a bad model, std::runtime_error for other failures
/// (kernels that do not match the model, a runner that cannot be built).
int verify(const VerifyOptions& options);

}  // namespace kanegen::verify
