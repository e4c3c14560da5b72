// SPDX-License-Identifier: GPL-2.0-or-later
// The whole generator as one call: model file -> Model -> kinematics ->
// Kane's equations -> expression graph -> emitted C++ files.
#pragma once

#include <map>
#include <string>

#include "codegen/kernel_splitter.hpp"
#include "codegen/kernel_table.hpp"
#include "codegen/model_kernels.hpp"
#include "codegen/scalar_type.hpp"
#include "model/load.hpp"

namespace kanegen::pipeline {

struct StageTimes {
  /// seconds: derive: M, f and the loops of each way of summing M; emit: the
  /// other products the kernels ask for (of the way kept), and the kernels printed
  double load = 0, derive = 0, emit = 0;
  double choose = 0;     ///< seconds: counting each derivation's composite forward_dynamics, to keep one
  double jacobians = 0;  ///< seconds: emitting with the Jacobian kernels (0 without them: then in emit)
};

struct GeneratedModel {
  std::string name;
  std::map<std::string, std::string> files;    ///< file name -> content
  std::map<codegen::Kernel, long> operations;  ///< operation count of each counted kernel
  codegen::DynamicsChoice dynamics;            ///< forward_dynamics's method and both counts
  std::size_t intermediates = 0;               ///< named intermediates of the derivation
  int nq = 0, nu = 0;
  StageTimes seconds;
};

/// What to generate beyond the kernels every model has.
struct GenerateOptions {
  /// The Jacobian kernels of implicit integration (`kanegen generate
  /// --jacobians`); off by default, since they can take longer to compile than the rest.
  bool jacobians = false;
  /// The quadratic controller kernels (`kanegen generate --controller`:
  /// coriolis_matrix, output_jacobian, output_jacobian_rate, linearize), with
  /// the Jacobian kernels they use; not for loops or prescribed motions.
  bool controller = false;
  /// The kernels' floating-point type (`--precision float`: <name>_float.hpp
  /// and .cpp, no runner; every kernel, closed loops included; not with the
  /// Jacobian or controller kernels).
  codegen::Precision precision = codegen::Precision::double_precision;
  /// How forward_dynamics solves (`--dynamics`): by operation count, or the
  /// articulated-body recursion or composite inertias + LDL^T as asked. The
  /// recursion is for trees (rigid or flexible) without loops or prescribed motions.
  codegen::DynamicsMethod dynamics = codegen::DynamicsMethod::automatic;
  /// `--split-threshold`: kernels of more statements are emitted as functions
  /// of at most this many (compile time linear in the model); 0: never.
  int split_threshold = codegen::kDefaultSplitThreshold;
  /// `--batch W` (4 or 8): also forward_dynamics and inverse_dynamics over W
  /// states at once, <name>_batch<W>.hpp and .cpp; 0 (the default): none.
  /// Double only, for trees without loops or prescribed motions.
  int batch = 0;
};

/// Runs every stage on the model file. Throws model::ModelError for a bad
/// model; the caller writes the files (see codegen::write_files_atomically).
GeneratedModel generate(const std::string& model_path, const model::LoadOptions& options = {},
                        const GenerateOptions& generate_options = {});

/// Hex digest (64-bit FNV-1a) of a byte string; stable across machines.
std::string digest(const std::string& bytes);
/// The bytes of a file; throws std::runtime_error naming the file.
std::string read_file(const std::string& path);

}  // namespace kanegen::pipeline
