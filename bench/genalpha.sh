#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Builds bench_genalpha (Release) and runs it: generalized-alpha at fixed
# steps on the spin-up beam (10 elements, Ws = 6 rad/s, 20 s) against DOPRI5
# at rtol 1e-8, with wall time, real-time factor (simulated / wall time),
# Newton statistics and the tip deflection's minimum. A benchmark, never a
# test: the times depend on the machine and its load.
#
# Environment (all optional):
#   KANEGEN_BENCH_BUILD_DIR  build directory (default: ${TMPDIR:-/tmp}/kanegen-build-bench-genalpha)
#   KANEGEN_BENCH_CXXFLAGS   CMAKE_CXX_FLAGS_RELEASE (default: "-O2 -DNDEBUG")
#   KANEGEN_BENCH_REPS       runs per configuration; the fastest is reported (default: 3)
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${KANEGEN_BENCH_BUILD_DIR:-${TMPDIR:-/tmp}/kanegen-build-bench-genalpha}"
flags="${KANEGEN_BENCH_CXXFLAGS:--O2 -DNDEBUG}"
reps="${KANEGEN_BENCH_REPS:-3}"
jobs="$(nproc 2>/dev/null || echo 2)"

cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=$flags" \
  -DKANEGEN_BUILD_BENCH=ON >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target bench_genalpha -j "$jobs"

compiler="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")"
echo "compiler: $compiler ($("$compiler" --version | head -n 1)), flags $flags"
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
"$build/bench/bench_genalpha" "$reps"
