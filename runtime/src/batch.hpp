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
        "eval": "all" | "udot" | "energy", "kinetic_energy_hessian": true,
        "inverse_dynamics_udot": [nu], "controller": true,
        "kernels": ["<kernel>", ...], "input_<argument>": [...]}
  out: {"mass_matrix": [[...]], "forcing": [...], "udot": [...], "pivot": k,
        "kinetic_energy": x, "potential_energy": y, "outputs": [...],
        "gravity": [...], "nonconservative_power": P,
        "kinetic_energy_hessian": [[...]], "inverse_dynamics": [...],
        "coriolis_matrix": [[...]], "output_jacobian": [[...]],
        "output_jacobian_rate": [...], "linearize_A": [[...]],
        "linearize_B": [[...]], "linearize_status": k,
        "kernels": {"<kernel>": {"<output>": [...], "returns": x}}}

q and u are required; t, tau default to 0; p (all parameters, in the order
of 'info') defaults to the model's defaults, for that line only. "eval"
selects the quantities: all (default), udot (udot and pivot only) or energy
(the two energies). pivot is 0, or k > 0 if the k-th pivot of M's LDL^T was
not positive (udot is then null). The Hessian of the kinetic energy in the
speeds is by second differences of kinetic_energy, exact up to round-off as
the energy is quadratic in u. gravity and nonconservative_power (with the
line's tau) come with "all". "inverse_dynamics_udot" asks for the
inverse_dynamics kernel at those accelerations; "controller": true for the
kernels of 'kanegen generate --controller' (an error without them).
"kernels" calls each kernel named (kernels.def: any the model's table
holds that takes arrays and scalars) through its spec, at the line's t, q,
u, tau; another input array is "input_<argument>" (e.g. "input_udot" for
inverse_dynamics, "input_a" for mass_matrix_product_jacobian). Its answer
gives each kernel's outputs by argument name, a matrix as its rows, and
"returns" unless the kernel returns nothing. A bad line gives
{"error": "..."} and the run goes on; the exit code is then 1.

options:
  -h, --help           show this help
)";

/// Runs the batch loop until end of input. Returns 0, or 1 if a line failed.
int run_batch(Model& model, std::FILE* in, std::FILE* out);

}  // namespace kanegen::runtime
