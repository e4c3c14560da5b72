#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Builds bench_dynamics (Release) and runs it: kanegen's generated kernels
# against MuJoCo on arm7 and chain20, then prints MuJoCo time / kanegen time
# per model. See docs/benchmarks.md.
#
# Environment (all optional):
#   KANEGEN_BENCH_BUILD_DIR  build directory      (default: ${TMPDIR:-/tmp}/kanegen-build-bench)
#   KANEGEN_BENCH_CXXFLAGS   CMAKE_CXX_FLAGS_RELEASE (default: "-O2 -DNDEBUG")
#   KANEGEN_BENCH_REPS       repetitions per benchmark; the median is reported (default: 5)
# Further arguments go to bench_dynamics (e.g. --benchmark_filter=arm7).
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${KANEGEN_BENCH_BUILD_DIR:-${TMPDIR:-/tmp}/kanegen-build-bench}"
flags="${KANEGEN_BENCH_CXXFLAGS:--O2 -DNDEBUG}"
reps="${KANEGEN_BENCH_REPS:-5}"
jobs="$(nproc 2>/dev/null || echo 2)"

cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=$flags" \
  -DKANEGEN_BUILD_TESTS=OFF -DKANEGEN_BUILD_BENCH=ON -DKANEGEN_WITH_MUJOCO=ON >"$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target bench_dynamics -j "$jobs"

compiler="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")"
echo "compiler: $compiler ($("$compiler" --version | head -n 1))"
echo "flags (kanegen kernels and bench): $(sed -n 's/^CMAKE_CXX_FLAGS:[A-Z]*=//p' "$build/CMakeCache.txt") $flags"
echo "MuJoCo: the distribution's prebuilt libmujoco (its own flags); contacts disabled"

json="$build/bench_dynamics.json"
"$build/bench/bench_dynamics" --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
  --benchmark_out="$json" --benchmark_out_format=json "$@"

python3 - "$json" <<'EOF'
import json, sys

with open(sys.argv[1]) as f:
    runs = json.load(f)["benchmarks"]
# median CPU time per benchmark (or the single run when there are no repetitions)
times = {}
for r in runs:
    if r.get("run_type") == "aggregate" and r.get("aggregate_name") != "median":
        continue
    times[r.get("run_name", r["name"])] = r["cpu_time"] * {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[r["time_unit"]]

pairs = [
    ("mujoco/mj_forward", "kanegen/forward_dynamics"),
    ("mujoco/mj_forward_lean", "kanegen/forward_dynamics"),
    ("mujoco/smooth", "kanegen/forward_dynamics"),
    ("mujoco/mass_matrix", "kanegen/mass_matrix"),
    ("mujoco/bias", "kanegen/forcing"),
    ("mujoco/mj_inverse", "kanegen/inverse_dynamics"),
    ("mujoco/rne", "kanegen/inverse_dynamics"),
    ("kanegen/M_udot_minus_f", "kanegen/inverse_dynamics"),
]
models = sorted({name.split("/")[0] for name in times})
# A batched kernel's call evaluates W states: its time per state is the call's / W.
for name in list(times):
    if "_batch" in name:
        times[name + "_per_state"] = times[name] / int(name.rsplit("_batch", 1)[1])
for w in (4, 8):
    pairs += [("mujoco/mj_forward", "kanegen/forward_dynamics_batch%d_per_state" % w),
              ("kanegen/forward_dynamics", "kanegen/forward_dynamics_batch%d_per_state" % w),
              ("mujoco/mj_inverse", "kanegen/inverse_dynamics_batch%d_per_state" % w),
              ("kanegen/inverse_dynamics", "kanegen/inverse_dynamics_batch%d_per_state" % w)]
print()
print("peer time / kanegen time (median CPU time per call; > 1 means kanegen is faster)")
print("%-9s %-24s %-42s %12s %12s %8s" % ("model", "peer", "kanegen", "peer [ns]", "kanegen [ns]", "ratio"))
for model in models:
    for mj, kg in pairs:
        a, b = times.get(model + "/" + mj), times.get(model + "/" + kg)
        if a is None or b is None:
            continue
        print("%-9s %-24s %-42s %12.1f %12.1f %8.2f" % (model, mj, kg, a, b, a / b))
EOF
