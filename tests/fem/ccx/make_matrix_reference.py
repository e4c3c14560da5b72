#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Writes the CalculiX matrices that the matrix import is tested on (tests/fem/data/matrices).

A small steel bar, 0.2 x 0.02 x 0.012 m, 6 x 2 x 1 C3D8 (make_solid_reference.py's
structured mesh and material), written as bar_c3d8_small.inp with node set ROOT
(the face x = 0), and for it, with CalculiX:

  clamped.sti, clamped.mas, clamped.dof
        *FREQUENCY, SOLVER=MATRIXSTORAGE with *BOUNDARY ROOT, 1, 3: K and M
        without the held dofs (what a "reduced" export holds)
  free.sti, free.mas, free.dof
        the same without *BOUNDARY: every dof
  bar_c3d8_small_ccx.txt
        *FREQUENCY of the same mesh, clamped (modes 1-12) and free (the first
        12 elastic modes, 7-18), as make_solid_reference.py writes them

Usage: tests/fem/ccx/make_matrix_reference.py [--ccx ccx]
(needs calculix-ccx; Debian: apt-get install calculix-ccx)
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_solid_reference as ref  # noqa: E402

OUT = os.path.join(ref.DATA, "matrices")
NAME = "bar_c3d8_small"
MODEL = {"type": "C3D8", "divisions": (6, 2, 1)}


def deck(mesh_text, clamped):
    m = ref.MATERIAL
    text = [mesh_text, "*MATERIAL, NAME=STEEL\n*ELASTIC\n", f"{m['E']:.12g}, {m['nu']:.12g}\n*DENSITY\n",
            f"{m['rho']:.12g}\n*SOLID SECTION, ELSET=EBODY, MATERIAL=STEEL\n"]
    if clamped:
        text.append("*BOUNDARY\nROOT, 1, 3\n")
    text.append("*STEP\n*FREQUENCY, SOLVER=MATRIXSTORAGE\n*END STEP\n")
    return "".join(text)


def write_matrices(ccx, mesh_text, support):
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "job.inp"), "w") as f:
            f.write(deck(mesh_text, support == "clamped"))
        log = subprocess.run([ccx, "job"], cwd=work, capture_output=True, text=True)
        if log.returncode != 0 or "ERROR" in log.stdout:
            sys.exit(f"ccx failed ({support}):\n{log.stdout}\n{log.stderr}")
        for ext in ("sti", "mas", "dof"):
            shutil.copy(os.path.join(work, "job." + ext), os.path.join(OUT, f"{support}.{ext}"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ccx", default="ccx")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    inp = os.path.join(OUT, NAME + ".inp")
    ref.write_structured(inp, NAME, MODEL)
    mesh = ref.mesh_for_ccx(inp, MODEL["type"])
    for support in ("clamped", "free"):
        write_matrices(args.ccx, mesh, support)
    results = {s: ref.run_ccx(args.ccx, mesh, MODEL["type"], s == "clamped") for s in ("clamped", "free")}
    m = ref.MATERIAL
    with open(os.path.join(OUT, NAME + "_ccx.txt"), "w") as f:
        f.write(f"# CalculiX {ref.ccx_version(args.ccx)} (C3D8, *FREQUENCY), mesh {NAME}.inp, "
                "by tests/fem/ccx/make_matrix_reference.py\n")
        f.write(f"# E {m['E']:.12g}\n# nu {m['nu']:.12g}\n# rho {m['rho']:.12g}\n")
        ref.write_frequencies(f, NAME, results)


if __name__ == "__main__":
    main()
