#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Mesh bodies against CalculiX (issue 39), in one run on this machine: a
steel CPS8 plate (0.3 x 0.05 m, 4 mm thick; tests/fem/ccx/make_solid_reference.py
writes the mesh) of NX x NY elements, clamped on its root edge (node set ROOT),
its first --modes modes as the elastic coordinates of a model (the plate on a
fixed joint), and

- `kanegen modes` on that model (wall time, the runner's cache empty: the
  reduction, the derivation, the compilation of the kernels and the
  linearisation), with this build's kanegen and with --baseline's (e.g. the
  dense path's build of main), and the frequencies of each;
- CalculiX's *FREQUENCY (`ccx`, calculix-ccx) on the same mesh and element
  type, the same number of modes (wall time), and its frequencies.

The frequencies of a clamped body's model are the mesh's own clamped ones, so
kanegen's equal CalculiX's to the difference of the two programs' plane
elements (CalculiX expands a CPS8 into a 3D brick: a few 1e-4 here;
tests/fem/test_calculix_continuum.cpp allows 0.5 %), and the two kanegen
builds' (sparse and dense path) to far below that.

    bench/mesh_modes.py [--nx 40] [--ny 8] [--modes 10] [--kanegen build/generator/kanegen]
                        [--baseline OTHER_KANEGEN] [--ccx ccx] [--out DIR]

A benchmark, not a test: nothing fails on time, and the times depend on the
machine and its load.
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "fem", "ccx"))
import make_solid_reference as ref  # noqa: E402  (the structured mesh writer and the ccx job)


def write_model(directory, mesh_file, modes):
    model = {
        "format": "kanegen-model",
        "version": 1,
        "name": "bench_plate",
        "description": "bench/mesh_modes.py: a clamped CPS8 plate on a fixed joint",
        "gravity": [0, 0, 0],
        "bodies": [{
            "name": "plate",
            "flexible": {
                "mesh": {"file": os.path.basename(mesh_file), "thickness": ref.PLATE["t"], "clamped_set": "ROOT"},
                "material": {"E": ref.MATERIAL["E"], "poisson": ref.MATERIAL["nu"], "density": ref.MATERIAL["rho"]},
                "modes": modes,
            },
        }],
        "joints": [{"name": "mount", "type": "fixed", "parent": "ground", "child": "plate"}],
    }
    path = os.path.join(directory, "bench_plate.json")
    with open(path, "w") as f:
        json.dump(model, f, indent=1)
    return path


def timed(work):
    """(wall s, CPU s of the child processes: user + system, result of work()). On a loaded
    machine the CPU time is the fairer figure: the wall time counts the other jobs too."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    result = work()
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), result


def kanegen_modes(kanegen, model, modes, directory):
    """(wall s, CPU s, omega rad/s list) of `kanegen modes` with an empty runner cache."""
    cache = tempfile.mkdtemp(prefix="cache-", dir=directory)
    env = dict(os.environ, XDG_CACHE_HOME=cache)
    wall, cpu, out = timed(lambda: subprocess.run([kanegen, "modes", model, "--count", str(modes), "--quiet"],
                                                  env=env, capture_output=True, text=True))
    if out.returncode != 0:
        sys.exit(f"{kanegen} modes failed:\n{out.stderr}")
    shutil.rmtree(cache, ignore_errors=True)
    return wall, cpu, [m["omega_rad_s"] for m in json.loads(out.stdout)["modes"]]


def ccx_modes(ccx, mesh_file, modes):
    ref.MODES = modes
    wall, cpu, freqs = timed(lambda: ref.run_ccx(ccx, ref.mesh_for_ccx(mesh_file, "CPS8"), "CPS8", True))
    return wall, cpu, [rad for _, rad, _ in freqs]


def worst(a, b):
    return max(abs(x / y - 1.0) for x, y in zip(a, b))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nx", type=int, default=40)
    parser.add_argument("--ny", type=int, default=8)
    parser.add_argument("--modes", type=int, default=10)
    parser.add_argument("--kanegen", default=os.path.join(ROOT, "build", "generator", "kanegen"))
    parser.add_argument("--baseline", help="another kanegen to time the same way (e.g. main's dense path)")
    parser.add_argument("--ccx", default="ccx")
    parser.add_argument("--out", help="keep the mesh, model and results here (default: a temporary directory)")
    args = parser.parse_args()
    directory = args.out or tempfile.mkdtemp(prefix="kanegen-mesh-modes-")
    os.makedirs(directory, exist_ok=True)
    mesh = os.path.join(directory, "bench_plate.inp")
    ref.write_structured(mesh, "bench_plate", {"type": "CPS8", "divisions": (args.nx, args.ny)})
    model = write_model(directory, mesh, args.modes)
    nodes = (2 * args.nx + 1) * (2 * args.ny + 1) - args.nx * args.ny
    print(f"CPS8 plate {args.nx} x {args.ny}: {nodes} nodes, {2 * nodes} dofs "
          f"({2 * nodes - 2 * (2 * args.ny + 1)} free), {args.modes} modes; files in {directory}")
    rows = [("ccx *FREQUENCY", *ccx_modes(shutil.which(args.ccx) or args.ccx, mesh, args.modes))]
    for label, kanegen in (("kanegen modes", args.kanegen), ("kanegen modes (baseline)", args.baseline)):
        if kanegen:
            rows.append((label, *kanegen_modes(kanegen, model, args.modes, directory)))
    ccx_cpu, ccx_omega = rows[0][2], rows[0][3]
    print("| run | wall s | CPU s | CPU x ccx | omega_1 rad/s | omega_last rad/s | max rel. diff. to ccx |")
    print("|---|---|---|---|---|---|---|")
    for label, wall, cpu, omega in rows:
        print(f"| {label} | {wall:.2f} | {cpu:.2f} | {cpu / max(ccx_cpu, 1e-3):.1f} | {omega[0]:.6f} | "
              f"{omega[-1]:.6f} | {worst(omega, ccx_omega):.2e} |")
    if len(rows) == 3:
        print(f"kanegen against the baseline: max rel. frequency difference {worst(rows[1][3], rows[2][3]):.2e}")
    with open(os.path.join(directory, "mesh_modes.json"), "w") as f:
        json.dump([{"run": r[0], "wall_s": r[1], "cpu_s": r[2], "omega": r[3]} for r in rows], f, indent=1)


if __name__ == "__main__":
    main()
