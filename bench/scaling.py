#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""How kanegen scales with model size (issue 17), in one run on this machine:
spatial chains of N links from scripts/make_chain_urdf.py, and for each

- the operation counts of forward_dynamics (both methods where the header
  gives them) and the method kanegen chose;
- generation time (`kanegen generate`, best of --reps, wall);
- compile time of the generated source at -O2 (g++, one run: CPU time, user
  plus system, and wall) and the source's size;
- forward_dynamics against MuJoCo's mj_forward on the same URDF, median time
  per call (bench/scaling_driver.cpp; it checks that both compute the same
  udot before it times anything), at --layouts placements of the kernel's
  code (the median over them counts);
- for the --sympy sizes, SymPy's KanesMethod on the same chain
  (bench/sympy_chain.py; its M and f at a check state must be kanegen's).

    bench/scaling.py [--sizes 7,20,50,100] [--sympy 7] [--kanegen build/generator/kanegen]
                     [--out DIR] [--reps 3] [--layouts 4] [--plot FIG.png] [--dynamics auto]
                     [--split-threshold N]
    bench/scaling.py --from-json DIR/scaling.json [--plot FIG.png]

Writes DIR/scaling.json and prints a markdown table; --plot draws operation
counts and the time ratio against N with gnuplot. A benchmark, not a test:
nothing fails on time, and the times depend on the machine and its load.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        sys.exit("bench/scaling.py: %s failed:\n%s%s" % (" ".join(command), result.stdout, result.stderr))
    return result


def wall(command, reps=1):
    best = float("inf")
    for _ in range(reps):
        start = time.perf_counter()
        run(command)
        best = min(best, time.perf_counter() - start)
    return best


def cpu(command):
    """CPU time (user + system) of the command's process and its children, and its wall time."""
    before = os.times()
    start = time.perf_counter()
    run(command)
    wall_seconds = time.perf_counter() - start
    after = os.times()
    return (after.children_user - before.children_user) + (after.children_system - before.children_system), wall_seconds


def operation_counts(header):
    """forward_dynamics's operation counts from the generated header's note,
    e.g. "forward_dynamics: 13603 (recursive; composite inertias and LDL^T: 15290)"
    or "forward_dynamics: 1851 (composite inertias, 252 of them in LDL^T; recursive: 2291)"."""
    for line in open(header):
        match = re.match(r"//\s+forward_dynamics:\s*(\d+)\s*\((.*)\)", line)
        if not match:
            continue
        chosen, note = int(match.group(1)), match.group(2)
        method = "recursive" if note.startswith("recursive") else "composite"
        other = re.search(r"(?:LDL\^T|recursive): (\d+)$", note)
        counts = {"chosen": chosen, method: chosen}
        if other:
            counts["composite" if method == "recursive" else "recursive"] = int(other.group(1))
        return counts, method
    sys.exit("bench/scaling.py: no forward_dynamics operation count in %s" % header)


def measure(args, n, work):
    urdf = os.path.join(work, "chain%d.urdf" % n)
    run([sys.executable, os.path.join(ROOT, "scripts", "make_chain_urdf.py"), "--links", str(n), "-o", urdf])
    gen = os.path.join(work, "gen%d" % n)
    shutil.rmtree(gen, ignore_errors=True)
    command = [args.kanegen, "generate", urdf, "-o", gen, "--quiet"]
    if args.dynamics:
        command += ["--dynamics", args.dynamics]
    if args.split_threshold is not None:
        command += ["--split-threshold", str(args.split_threshold)]
    print("chain%d: generating ..." % n, file=sys.stderr, flush=True)
    generation = wall(command, args.reps)
    name = "chain%d" % n
    counts, method = operation_counts(os.path.join(gen, name + ".hpp"))
    print("chain%d: compiling at -O2 ..." % n, file=sys.stderr, flush=True)
    obj = os.path.join(work, name + ".o")
    compile_cpu, compile_seconds = cpu([args.cxx, "-std=c++17", "-O2", "-I", gen, "-I", os.path.join(ROOT, "runtime", "include"),
                            "-c", os.path.join(gen, name + ".cpp"), "-o", obj])
    driver_object = os.path.join(work, "driver%d.o" % n)
    run([args.cxx, "-std=c++17", "-O2", "-DKANEGEN_SCALING_HEADER=<%s.hpp>" % name,
         "-DKANEGEN_SCALING_NAMESPACE=%s" % name, "-I", gen, "-c", os.path.join(ROOT, "bench", "scaling_driver.cpp"),
         "-o", driver_object])
    # Where the kernel's code lands moves its time by up to about 20 % (fetch
    # blocks and cache lines; see docs/benchmarks.md), as much as a change
    # to the kernel may gain. So the same object is linked at --layouts
    # offsets, 16 bytes apart (padding before it), and each figure is the
    # median over them.
    print("chain%d: timing forward_dynamics and mj_forward at %d code layouts ..." % (n, args.layouts),
          file=sys.stderr, flush=True)
    layouts = []
    for k in range(args.layouts):
        pad = os.path.join(work, "pad%d.s" % k)
        with open(pad, "w") as f:
            f.write(".section .note.GNU-stack,\"\",@progbits\n.text\n.globl kanegen_layout_pad%d\n"
                    "kanegen_layout_pad%d:\n%s" % (k, k, ".space %d, 0x90\n" % (16 * k) if k else ""))
        driver = os.path.join(work, "driver%d_layout%d" % (n, k))
        run([args.cxx, driver_object, pad, obj, "-lmujoco", "-o", driver])
        layouts.append(json.loads(run([driver, urdf]).stdout))
    timing = dict(layouts[0])
    for key in ("kanegen_ns", "mujoco_ns"):
        timing[key] = statistics.median(t[key] for t in layouts)
    ratios = [t["kanegen_ns"] / t["mujoco_ns"] for t in layouts]
    return {"links": n, "method": method, "operations": counts, "generation_s": generation,
            "source_bytes": os.path.getsize(os.path.join(gen, name + ".cpp")), "compile_O2_s": compile_seconds,
            "compile_O2_cpu_s": compile_cpu, **timing, "ratio_to_mj_forward": statistics.median(ratios),
            "layouts": {"kanegen_ns": [t["kanegen_ns"] for t in layouts],
                        "mujoco_ns": [t["mujoco_ns"] for t in layouts], "ratio": ratios}}


def sympy_peer(n, kanegen_row, timeout):
    print("chain%d: SymPy KanesMethod ..." % n, file=sys.stderr, flush=True)
    try:
        result = subprocess.run([sys.executable, os.path.join(ROOT, "bench", "sympy_chain.py"), str(n)],
                                capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"links": n, "seconds": None, "note": "over %d s" % timeout}
    if result.returncode != 0:
        return {"links": n, "seconds": None, "note": "failed: " + result.stderr.strip().splitlines()[-1]}
    row = json.loads(result.stdout)
    if kanegen_row is not None:
        for key in ("mass", "forcing"):
            ours, theirs = kanegen_row[key], row[key]
            scale = max(1.0, max(abs(x) for x in ours))
            worst = max(abs(a - b) for a, b in zip(ours, theirs)) / scale if len(ours) == len(theirs) else float("inf")
            if not worst < 1e-9:
                sys.exit("bench/scaling.py: SymPy's %s differs from kanegen's by %g (relative): not the same model" %
                         (key, worst))
            row["max_%s_difference" % key] = worst
            del row[key]
        row["kanegen_generation_s"] = kanegen_row["generation_s"]
    return row


def plot(rows, path):
    data = path + ".dat"
    with open(data, "w") as f:
        for r in rows:
            f.write("%d %d %g\n" % (r["links"], r["operations"].get("chosen", 0), r["ratio_to_mj_forward"]))
    script = """set terminal pngcairo size 900,420 font ',10' noenhanced
set output '%s'
set multiplot layout 1,2
set xlabel 'links N'
set xrange [5:150]
set ylabel 'operations in forward_dynamics'
set logscale xy
set key top left
plot '%s' using 1:2 with linespoints title 'kanegen', '' using 1:(500*$1) with lines dashtype 2 title '500 N'
unset logscale y
set logscale x
set ylabel 'time / mj_forward'
set yrange [0:*]
plot '%s' using 1:3 with linespoints title 'forward_dynamics / mj_forward'
unset multiplot
""" % (path, data, data)
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.remove(data)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="7,20,50,100", help="chain lengths (default 7,20,50,100)")
    parser.add_argument("--sympy", default="7", help="chain lengths for the SymPy peer, '' for none (default 7)")
    parser.add_argument("--sympy-timeout", type=int, default=1800, help="seconds per SymPy run (default 1800)")
    parser.add_argument("--kanegen", default=os.path.join(ROOT, "build", "generator", "kanegen"))
    parser.add_argument("--cxx", default="g++")
    parser.add_argument("--dynamics", default="", help="passed to kanegen generate --dynamics (default: its own)")
    parser.add_argument("--split-threshold", type=int, default=None,
                        help="passed to kanegen generate --split-threshold (default: its own)")
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "bench_scaling"))
    parser.add_argument("--reps", type=int, default=3, help="generation runs per size; the fastest counts")
    parser.add_argument("--layouts", type=int, default=4,
                        help="code layouts the kernel is timed at (its object 16 bytes further each); the"
                             " figures are their median (default 4)")
    parser.add_argument("--plot", help="write a PNG of operations and time ratio against N")
    parser.add_argument("--from-json", metavar="FILE",
                        help="measure nothing: print the tables (and --plot) of an earlier run's scaling.json")
    args = parser.parse_args()
    if args.layouts < 1:
        parser.error("--layouts must be at least 1")
    if args.from_json:
        with open(args.from_json) as f:
            report(json.load(f), args.plot)
        return
    if not os.access(args.kanegen, os.X_OK):
        sys.exit("bench/scaling.py: no kanegen at %s (build it, or pass --kanegen)" % args.kanegen)
    os.makedirs(args.out, exist_ok=True)
    sizes = [int(s) for s in args.sizes.split(",") if s]
    sympy_sizes = [int(s) for s in args.sympy.split(",") if s]
    rows = [measure(args, n, args.out) for n in sorted(set(sizes) | set(sympy_sizes))]
    by_size = {r["links"]: r for r in rows}
    peers = [sympy_peer(n, by_size.get(n), args.sympy_timeout) for n in sympy_sizes]
    rows = [r for r in rows if r["links"] in sizes]
    result = {"machine": {"cores": os.cpu_count(), "load": os.getloadavg()}, "chains": rows, "sympy": peers}
    with open(os.path.join(args.out, "scaling.json"), "w") as f:
        json.dump(result, f, indent=2)
    report(result, args.plot)


def report(result, plot_path):
    """The markdown tables of a run's result, and its plot if asked for."""
    rows, peers = result["chains"], result["sympy"]
    print("machine: %d cores, load %.1f %.1f %.1f" % ((result["machine"]["cores"],) + tuple(result["machine"]["load"])))
    print()
    print("| links | method | operations (chosen; recursive / composite) | generation [s] | source [MB] |"
          " compile -O2 CPU [s] | compile -O2 wall [s] | forward_dynamics [us] | mj_forward [us] | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        c = r["operations"]
        both = " / ".join(str(c[k]) if k in c else "-" for k in ("recursive", "composite"))
        print("| %d | %s | %d (%s) | %.2f | %.2f | %.1f | %.1f | %.2f | %.2f | %.3f |" %
              (r["links"], r["method"], c.get("chosen", 0), both, r["generation_s"], r["source_bytes"] / 1e6,
               r["compile_O2_cpu_s"], r["compile_O2_s"],
               r["kanegen_ns"] / 1e3, r["mujoco_ns"] / 1e3, r["ratio_to_mj_forward"]))
    spread = [r for r in rows if len(r.get("layouts", {}).get("ratio", [])) > 1]
    if spread:
        print()
        print("| links | ratio at each code layout (the table gives their median) |")
        print("|---|---|")
        for r in spread:
            print("| %d | %s |" % (r["links"], ", ".join("%.3f" % x for x in r["layouts"]["ratio"])))
    if peers:
        print()
        print("| links | SymPy KanesMethod [s] (CPU, equations only) | kanegen generate [s] (wall, to C++) |")
        print("|---|---|---|")
        for p in peers:
            sympy_time = "%.1f" % p["seconds"] if p.get("seconds") is not None else p.get("note", "-")
            print("| %d | %s | %.2f |" % (p["links"], sympy_time, p.get("kanegen_generation_s", float("nan"))))
    if plot_path:
        plot(rows, plot_path)
        print("\nwrote %s" % plot_path)


if __name__ == "__main__":
    main()
