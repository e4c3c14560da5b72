// SPDX-License-Identifier: MIT
// The runner's `batch` command (private to the runtime): evaluates the
// model at states read as JSON lines from a stream, one JSON line out per
// line in, flushed at once, so that a caller can keep the runner open as a
// coprocess (kanegen verify) or pipe a file of states through it.
#pragma once

#include <cstdio>

#include "kanegen/runtime/model.hpp"

namespace kanegen::runtime {

constexpr const char* kBatchUsage = R"(usage: PROG batch < states.jsonl

Reads one JSON object per line from standard input and writes one JSON
object per line to standard output (flushed after each line):

  in:  {"t": T, "q": [nq], "u": [nu], "tau": [ntau], "p": [np],
        "kernels": ["<kernel>", ...], "input_<argument>": [...]}
  out: {"kernels": {"<kernel>": {"<output>": [...], "returns": x}, ...}}

q, u and kernels are required; t, tau default to 0; p (all parameters, in
the order of 'info') defaults to the model's defaults, for that line only.
"kernels" calls each kernel named (kernels.def: any the model's table holds
that takes arrays and scalars) through its spec, at the line's t, q, u, tau;
another input array is "input_<argument>" (e.g. "input_udot" for
inverse_dynamics, "input_a" for mass_matrix_product_jacobian). The answer
gives each kernel's outputs by argument name, a matrix as its rows, and
"returns" unless the kernel returns nothing (forward_dynamics' pivot: 0, or
k > 0 if the k-th pivot was not positive; an energy). A kernel the model
lacks is an error saying which option brings it. A bad line gives
{"error": "..."} and the run goes on; the exit code is then 1.

options:
  -h, --help           show this help
)";

/// Runs the batch loop until end of input. Returns 0, or 1 if a line failed.
int run_batch(Model& model, std::FILE* in, std::FILE* out);

}  // namespace kanegen::runtime
