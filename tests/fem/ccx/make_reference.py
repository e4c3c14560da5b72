#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Writes the CalculiX reference data of the finite-element tests (tests/fem/data).

Two models, both slender steel beams with a square section (L/a >= 160, so the
shear deformation and rotary inertia that CalculiX's B31 elements carry, being
expanded into 3D bricks, change the frequencies by far less than 1 %):

  l_frame     two legs at a right angle in the x-y plane, clamped at the origin:
              leg 1 along x, leg 2 from its end along y;
  cantilever  a straight cantilever of the same section, whose torsional
              frequency shows the torsion constant CalculiX's expanded B31
              section has: the polar moment a^4 / 6 (the single brick across the
              section does not warp), not Saint-Venant's 0.1406 a^4. The tests
              therefore give their beams J = Ip for this comparison.

For each model this writes NAME.inp (the input CalculiX ran) and NAME_ccx.txt
(parameters as "# key value" lines, then "mode omega_rad_s frequency_hz").

Usage: tests/fem/ccx/make_reference.py [--ccx ccx]   (needs calculix-ccx; Debian: apt-get install calculix-ccx)
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")

MATERIAL = {"E": 2.1e11, "nu": 0.3, "rho": 7850.0}
SIDE = 0.005  # square section side a, m

MODELS = {
    # legs: end point and element count of each straight run, starting at the origin;
    # modes: how many to extract (the cantilever's first torsion mode is its 15th).
    # B31 is linear (expanded into linear bricks), so the mesh is fine enough for the
    # reference to be converged: with 20 elements per leg mode 10 is still 1 % stiff,
    # with 160 it is within 0.02 % of 320.
    "l_frame": {"legs": [((1.0, 0.0, 0.0), 160), ((1.0, 0.8, 0.0), 160)], "modes": 12},
    "cantilever": {"legs": [((0.8, 0.0, 0.0), 160)], "modes": 16},
}


def nodes_and_elements(legs):
    nodes = [(0.0, 0.0, 0.0)]
    elements = []
    for end, count in legs:
        start = nodes[-1]
        for i in range(1, count + 1):
            nodes.append(tuple(s + (e - s) * i / count for s, e in zip(start, end)))
            elements.append((len(nodes) - 1, len(nodes)))  # 1-based node ids: previous, new
    return nodes, elements


def write_inp(path, model):
    nodes, elements = nodes_and_elements(model["legs"])
    with open(path, "w") as f:
        f.write("** kanegen tests/fem reference, written by tests/fem/ccx/make_reference.py\n")
        f.write("*NODE, NSET=NALL\n")
        for i, (x, y, z) in enumerate(nodes, start=1):
            f.write(f"{i}, {x:.12g}, {y:.12g}, {z:.12g}\n")
        f.write("*ELEMENT, TYPE=B31, ELSET=EALL\n")
        for i, (a, b) in enumerate(elements, start=1):
            f.write(f"{i}, {a}, {b}\n")
        f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n")
        f.write(f"{MATERIAL['E']:.12g}, {MATERIAL['nu']:.12g}\n*DENSITY\n{MATERIAL['rho']:.12g}\n")
        # Section axis 1 along global z: normal to every leg of these models.
        f.write("*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=RECT\n")
        f.write(f"{SIDE:.12g}, {SIDE:.12g}\n0.0, 0.0, 1.0\n")
        f.write("*BOUNDARY\n1, 1, 6\n")
        f.write(f"*STEP\n*FREQUENCY\n{model['modes']}\n*END STEP\n")


def run_ccx(ccx, inp, modes):
    with tempfile.TemporaryDirectory() as work:
        shutil.copy(inp, os.path.join(work, "job.inp"))
        log = subprocess.run([ccx, "job"], cwd=work, capture_output=True, text=True)
        if log.returncode != 0 or "ERROR" in log.stdout:
            sys.exit(f"ccx failed on {inp}:\n{log.stdout}\n{log.stderr}")
        with open(os.path.join(work, "job.dat")) as f:
            dat = f.read()
    block = dat.split("E I G E N V A L U E   O U T P U T", 1)[1]
    rows = re.findall(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", block, re.M)
    freqs = [(int(m), float(rad), float(hz)) for m, _, rad, hz, _ in rows[:modes]]
    if len(freqs) != modes:
        sys.exit(f"expected {modes} eigenvalues in the output of {inp}")
    return freqs


def ccx_version(ccx):
    out = subprocess.run([ccx, "-v"], capture_output=True, text=True).stdout
    match = re.search(r"Version\s+(\S+)", out)
    return match.group(1) if match else "unknown"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ccx", default="ccx")
    args = parser.parse_args()
    version = ccx_version(args.ccx)
    for name, model in MODELS.items():
        inp = os.path.join(DATA, name + ".inp")
        write_inp(inp, model)
        freqs = run_ccx(args.ccx, inp, model["modes"])
        with open(os.path.join(DATA, name + "_ccx.txt"), "w") as f:
            f.write(f"# CalculiX {version} (B31, *FREQUENCY), input {name}.inp, by tests/fem/ccx/make_reference.py\n")
            f.write(f"# E {MATERIAL['E']:.12g}\n# nu {MATERIAL['nu']:.12g}\n# rho {MATERIAL['rho']:.12g}\n")
            f.write(f"# side {SIDE:.12g}\n")
            for i, (end, count) in enumerate(model["legs"]):
                f.write(f"# leg{i} {end[0]:.12g} {end[1]:.12g} {end[2]:.12g} {count}\n")
            f.write("# mode omega_rad_s frequency_hz\n")
            for mode, rad, hz in freqs:
                f.write(f"{mode} {rad:.7e} {hz:.7e}\n")
        print(f"{name}: " + ", ".join(f"{rad:.6g}" for _, rad, _ in freqs) + " rad/s")


if __name__ == "__main__":
    main()
