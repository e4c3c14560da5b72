// SPDX-License-Identifier: GPL-2.0-or-later
// Batched kernels (`kanegen generate --batch W`): forward_dynamics and
// inverse_dynamics evaluated over W states at once, from the scalar kernels'
// own straight-line code with every value a vector of W lanes (a GCC/Clang
// vector extension type, or a portable struct of W doubles). The emitted
// <name>_batch<W>.hpp and .cpp come beside the model's files, which they
// include; the model's own files do not change.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "codegen/kernel_printer.hpp"

namespace kanegen::codegen {

/// The kernels that have a batched form.
bool has_batch_form(Kernel kernel);

/// The statements of a scalar kernel's body (double) for W lanes: every
/// `double` a `Lanes`, an assigned value made a vector (`lanes_zero + (...)`,
/// exact), <math.h> calls lane by lane, and each pivot check
/// `if (!(d > 0.0)) return k;` a check per lane that records k in that lane's
/// status unless an earlier one did. The final `return 0;` is dropped (the
/// caller stores the outputs and counts the failed lanes). Throws
/// std::logic_error on a statement it does not know how to batch (a branch,
/// a loop, another return), so that nothing is batched wrong silently.
std::string batch_body(const std::string& scalar_body);

/// <emitted name>_batch<W>.hpp and .cpp with the batched forms of the
/// kernels in `kernels` that have one. `values`: the model template's values
/// (MODEL_NAME, GENERATOR_VERSION, MODEL_FILE, MODEL_HASH). W is 4 or 8.
std::map<std::string, std::string> batch_files(const std::vector<KernelCode>& kernels,
                                               const std::map<std::string, std::string>& values, int lanes);

}  // namespace kanegen::codegen
