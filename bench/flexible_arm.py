#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""The flexible arm of issue 17 (models/flexible_arm10.json: 10 spatial
flexible links, 4 modes each, 50 coordinates), in one run on this machine:
for each forward_dynamics method (recursive, composite)

- the operation counts (from the generated header);
- generation time (`kanegen generate`, best of --reps, wall);
- compile time of the generated source at -O2 (g++, one run, wall);
- forward_dynamics, median time per call over 64 states
  (bench/flexible_driver.cpp; it checks that u_dot solves the same kernels'
  M u_dot = f before timing, and this script checks that both methods give
  the same u_dot).

    bench/flexible_arm.py [--model models/flexible_arm10.json] [--kanegen build/generator/kanegen]
                          [--out DIR] [--reps 3] [--cxx g++]

Writes DIR/flexible_arm.json and prints a markdown table. A benchmark, not a
test: nothing fails on time, and the times depend on the machine and its load.
"""
import argparse
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scaling import ROOT, operation_counts, run, wall  # noqa: E402


def measure(args, method):
    name = os.path.splitext(os.path.basename(args.model))[0]
    gen = os.path.join(args.out, method)
    shutil.rmtree(gen, ignore_errors=True)
    print("%s, %s: generating ..." % (name, method), file=sys.stderr, flush=True)
    generation = wall([args.kanegen, "generate", args.model, "-o", gen, "--quiet", "--dynamics", method], args.reps)
    counts, _ = operation_counts(os.path.join(gen, name + ".hpp"))
    source = os.path.join(gen, name + ".cpp")
    obj = os.path.join(gen, name + ".o")
    include = ["-I", gen, "-I", os.path.join(ROOT, "runtime", "include")]
    print("%s, %s: compiling at -O2 ..." % (name, method), file=sys.stderr, flush=True)
    compile_seconds = wall([args.cxx, "-std=c++17", "-O2"] + include + ["-c", source, "-o", obj])
    driver = os.path.join(gen, "driver")
    run([args.cxx, "-std=c++17", "-O2", "-DKANEGEN_FLEX_HEADER=<%s.hpp>" % name, "-DKANEGEN_FLEX_NAMESPACE=%s" % name,
         "-I", "/usr/include/eigen3"] + include + [os.path.join(ROOT, "bench", "flexible_driver.cpp"), obj,
                                                    "-o", driver])
    timing = json.loads(run([driver]).stdout)
    return {"method": method, "operations": counts, "generation_s": generation, "source_bytes": os.path.getsize(source),
            "compile_O2_s": compile_seconds, **timing}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default=os.path.join(ROOT, "models", "flexible_arm10.json"))
    parser.add_argument("--kanegen", default=os.path.join(ROOT, "build", "generator", "kanegen"))
    parser.add_argument("--cxx", default="g++")
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "bench_flexible_arm"))
    parser.add_argument("--reps", type=int, default=3, help="generation runs per method; the fastest counts")
    args = parser.parse_args()
    if not os.access(args.kanegen, os.X_OK):
        sys.exit("bench/flexible_arm.py: no kanegen at %s (build it, or pass --kanegen)" % args.kanegen)
    os.makedirs(args.out, exist_ok=True)
    rows = [measure(args, method) for method in ("recursive", "composite")]
    a, b = rows[0]["udot"], rows[1]["udot"]
    # Relative to max |u_dot|: M is ill-conditioned (stiff modes beside the joints).
    difference = max(abs(x - y) for x, y in zip(a, b)) / max(abs(y) for y in b)
    if not difference < 1e-8:
        sys.exit("bench/flexible_arm.py: recursive and composite u_dot differ: relative %.3g" % difference)
    result = {"machine": {"cores": os.cpu_count(), "load": os.getloadavg()}, "model": args.model,
              "udot_recursive_vs_composite": difference, "methods": rows}
    with open(os.path.join(args.out, "flexible_arm.json"), "w") as f:
        json.dump(result, f, indent=2)
    print("machine: %d cores, load %.1f %.1f %.1f" % ((os.cpu_count(),) + os.getloadavg()))
    print("u_dot, recursive vs composite: max relative difference %.2e" % difference)
    print()
    print("| method | operations | source [MB] | generation [s] | compile -O2 [s] | forward_dynamics [us] |"
          " backward error | condition of M |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | %.2f | %.2f | %.1f | %.2f | %.1e | %.1e |" %
              (r["method"], r["operations"]["chosen"], r["source_bytes"] / 1e6, r["generation_s"], r["compile_O2_s"],
               r["forward_dynamics_ns"] / 1e3, r["backward_error"], r["condition_of_M"]))
    print("\nratio recursive / composite: %.2f" % (rows[0]["forward_dynamics_ns"] / rows[1]["forward_dynamics_ns"]))


if __name__ == "__main__":
    main()
