// SPDX-License-Identifier: GPL-2.0-or-later
// Emission: fills the templates with the printed kernels of a model and
// writes <name>.hpp, <name>.cpp and <name>_runner.cpp atomically.
#pragma once

#include <map>
#include <string>

#include "codegen/expression_graph.hpp"
#include "codegen/kernel_splitter.hpp"
#include "codegen/kernel_table.hpp"
#include "codegen/model_kernels.hpp"
#include "codegen/scalar_type.hpp"
#include "kane/equations.hpp"
#include "model/model.hpp"
#include "symbolic/program.hpp"
#include "symbolic/variables.hpp"

namespace kanegen::codegen {

struct EmittedModel {
  std::map<std::string, std::string> files;  ///< file name -> content
  std::map<Kernel, long> operations;         ///< operation count of each counted kernel
  DynamicsChoice dynamics;                   ///< how forward_dynamics solves, with both counts
};

/// What a model's code holds beyond the kernels every model has.
struct EmitOptions {
  /// The Jacobian kernels of implicit integration (forcing_jacobian, ...):
  /// optional because they can take longer to compile than the rest.
  bool jacobians = false;
  /// The quadratic controller kernels (coriolis_matrix, output Jacobians,
  /// linearize); they need `jacobians` too.
  bool controller = false;
  /// The floating-point type of the kernels. Float models (not with loops or
  /// Jacobians) are named <name>_float and have no runner and no runtime face.
  Precision precision = Precision::double_precision;
  /// forward_dynamics's method; `recursive` needs a rigid tree without loops
  /// or prescribed motions (kane::Recursion::unavailable says why not).
  DynamicsMethod dynamics = DynamicsMethod::automatic;
  /// Kernels of more statements are split into functions of at most this
  /// many, so that the compile time grows linearly (kernel_splitter.hpp); 0: never.
  int split_threshold = kDefaultSplitThreshold;
  /// 4 or 8: also <name>_batch<W>.hpp and .cpp, forward_dynamics and
  /// inverse_dynamics over W states at once (batch_kernels.hpp); 0: none.
  /// Double only, for trees without loops or prescribed motions.
  int batch = 0;
};

/// The name of the emitted files and namespace: the model's, "_float" added for float.
std::string emitted_name(const std::string& model_name, const ScalarType& scalar);

/// The model's files, its kernels derived from `products` on `graph` (a
/// graph of their program, which may already hold some of them, e.g. from
/// codegen::composite_operations: the text does not depend on what it held).
/// model_hash: a digest of the model file, quoted in the header comment.
EmittedModel emit_model(kane::DerivationContext& products, ExpressionGraph& graph,
                        const std::string& model_hash, const EmitOptions& options = {});

/// Replaces every {{KEY}} of `text`; throws std::logic_error on a key left over.
std::string fill_template(const std::string& text, const std::map<std::string, std::string>& values);

/// Writes each file to dir/name through a temporary file and a rename, so a
/// failure never leaves a half-written file; creates dir if needed.
void write_files_atomically(const std::string& dir, const std::map<std::string, std::string>& files);

}  // namespace kanegen::codegen
