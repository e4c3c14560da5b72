#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Writes the CalculiX buckling references of the plane and solid elements (tests/fem/data).

Slender steel columns clamped at x = 0 (node set ROOT) and compressed at
x = L by an axial force P (the consistent nodal forces of a uniform traction on
the end face, so both codes load the same nodes alike), run with CalculiX's
*BUCKLE on the same mesh and element type:

  column_c3d20  solid bar 0.3 x 0.02 x 0.012 m, 15 x 2 x 1 C3D20 (buckles in z)
  column_c3d8   the same bar, 30 x 2 x 2 C3D8
  strip_cps8    plane-stress strip 0.3 x 0.01 m, t 4 mm, 30 x 2 CPS8 (buckles in y)

For each this writes NAME.inp (the mesh, from make_solid_reference.py's
structured mesher) and NAME_ccx.txt: parameters as "# key value" lines,
"load node_id direction force_N" lines (direction 1 = x), then
"mode buckling_factor" for the first BUCKLING_MODES modes: the critical load
is the factor times P.

Usage: tests/fem/ccx/make_buckle_reference.py [--ccx ccx]
(needs calculix-ccx; Debian: apt-get install calculix-ccx)
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_solid_reference as solid  # noqa: E402  (the mesher, material and ccx helpers)

DATA = solid.DATA
MATERIAL = solid.MATERIAL
LOAD = 1000.0  # N, compressive
BUCKLING_MODES = 4

MODELS = {
    "column_c3d20": {"type": "C3D20", "divisions": (15, 2, 1), "sizes": (0.3, 0.02, 0.012)},
    "column_c3d8": {"type": "C3D8", "divisions": (30, 2, 2), "sizes": (0.3, 0.02, 0.012)},
    "strip_cps8": {"type": "CPS8", "divisions": (30, 2), "sizes": (0.3, 0.01), "thickness": 0.004},
}

# Consistent nodal forces of a uniform traction, as fractions of the face's load, by the face
# nodes' natural coordinates: line edges (1/2, 1/2), quadratic edges (1/6, 2/3, 1/6), bilinear
# faces 1/4 each, serendipity faces -1/12 at the corners and 1/3 at the mid-edge nodes.
def face_fraction(etype, rest):
    on_mid = sum(1 for c in rest if c == 0)
    if etype == "CPS4":
        return 0.5
    if etype == "CPS8":
        return 2.0 / 3.0 if on_mid else 1.0 / 6.0
    if etype == "C3D8":
        return 0.25
    return 1.0 / 3.0 if on_mid else -1.0 / 12.0


def end_loads(etype, divisions, elements):
    """{node id: x force} for the total force -LOAD spread over the x = L face."""
    local = solid.QUAD if len(divisions) == 2 else solid.HEX
    faces = 1
    for n in divisions[1:]:
        faces *= n
    cells = sorted(solid._cells(divisions))
    loads = {}
    for cell, nodes in zip(cells, elements):
        if cell[0] != divisions[0] - 1:
            continue
        for node, c in zip(nodes, local):
            if c[0] == 1:
                loads[node] = loads.get(node, 0.0) - LOAD / faces * face_fraction(etype, c[1:])
    return dict(sorted(loads.items()))


def write_mesh(path, name, model):
    coords, elements = solid.structured_mesh(model["type"], model["divisions"], model["sizes"])
    root = sorted(i for i, x in enumerate(coords, start=1) if x[0] == 0.0)
    with open(path, "w") as f:
        f.write(f"** kanegen tests/fem buckling mesh {name}, written by tests/fem/ccx/make_buckle_reference.py\n")
        f.write("*NODE, NSET=NALL\n")
        for i, x in enumerate(coords, start=1):
            f.write(f"{i}, " + ", ".join(f"{v:.12g}" for v in x) + "\n")
        f.write(f"*ELEMENT, TYPE={model['type']}, ELSET=EBODY\n")
        for i, nodes in enumerate(elements, start=1):
            first, rest = nodes[:10], nodes[10:]
            f.write(f"{i}, " + ", ".join(map(str, first)) + ("," if rest else "") + "\n")
            if rest:
                f.write(", ".join(map(str, rest)) + "\n")
        f.write("*NSET, NSET=ROOT\n")
        for k in range(0, len(root), 8):
            f.write(", ".join(map(str, root[k : k + 8])) + "\n")
    return elements


def run_buckle(ccx, mesh_text, model, loads):
    etype = model["type"]
    plane = etype.startswith("CPS")
    deck = [mesh_text, "*MATERIAL, NAME=STEEL\n*ELASTIC\n",
            f"{MATERIAL['E']:.12g}, {MATERIAL['nu']:.12g}\n*DENSITY\n{MATERIAL['rho']:.12g}\n",
            "*SOLID SECTION, ELSET=EBODY, MATERIAL=STEEL\n"]
    if plane:
        deck.append(f"{model['thickness']:.12g}\n")
    deck.append(f"*BOUNDARY\nROOT, 1, {2 if plane else 3}\n")
    deck.append(f"*STEP\n*BUCKLE\n{BUCKLING_MODES}\n*CLOAD\n")
    deck.extend(f"{node}, 1, {force:.15g}\n" for node, force in loads.items())
    deck.append("*END STEP\n")
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "job.inp"), "w") as f:
            f.write("".join(deck))
        log = subprocess.run([ccx, "job"], cwd=work, capture_output=True, text=True)
        if log.returncode != 0 or "ERROR" in log.stdout:
            sys.exit(f"ccx failed ({etype}):\n{log.stdout}\n{log.stderr}")
        with open(os.path.join(work, "job.dat")) as f:
            dat = f.read()
    block = dat.split("B U C K L I N G   F A C T O R   O U T P U T", 1)[1]
    rows = re.findall(r"^\s*(\d+)\s+(\S+)\s*$", block, re.M)
    factors = [(int(m), float(v)) for m, v in rows][:BUCKLING_MODES]
    if len(factors) != BUCKLING_MODES:
        sys.exit(f"expected {BUCKLING_MODES} buckling factors ({etype}):\n{block}")
    return factors


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ccx", default="ccx")
    args = parser.parse_args()
    version = solid.ccx_version(args.ccx)
    for name, model in MODELS.items():
        inp = os.path.join(DATA, name + ".inp")
        elements = write_mesh(inp, name, model)
        loads = end_loads(model["type"], model["divisions"], elements)
        factors = run_buckle(args.ccx, solid.mesh_for_ccx(inp, model["type"]), model, loads)
        with open(os.path.join(DATA, name + "_ccx.txt"), "w") as f:
            f.write(f"# CalculiX {version} ({model['type']}, *BUCKLE), mesh {name}.inp, "
                    "by tests/fem/ccx/make_buckle_reference.py\n")
            f.write(f"# E {MATERIAL['E']:.12g}\n# nu {MATERIAL['nu']:.12g}\n# rho {MATERIAL['rho']:.12g}\n")
            for key, value in zip(("length", "height", "depth"), model["sizes"]):
                f.write(f"# {key} {value:.12g}\n")
            if "thickness" in model:
                f.write(f"# thickness {model['thickness']:.12g}\n")
            f.write(f"# load {LOAD:.12g}\n")
            f.write("# load node direction force_N; then mode buckling_factor\n")
            for node, force in loads.items():
                f.write(f"load {node} 1 {force:.15g}\n")
            for mode, factor in factors:
                f.write(f"buckle {mode} {factor:.7e}\n")
        print(f"{name}: buckling factors " + ", ".join(f"{v:.6g}" for _, v in factors)
              + f" (P = {LOAD:g} N)")


if __name__ == "__main__":
    main()
