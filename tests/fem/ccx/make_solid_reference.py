#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Writes the CalculiX references of the plane and solid elements (tests/fem/data).

Four meshes of steel cantilevers and a shipped solid connecting rod, each run
clamped at its root (node set ROOT; the rod: BIG_END) and free-free, with
CalculiX's *FREQUENCY on the same mesh and element type:

  plate_cps4   plane-stress plate 0.3 x 0.05 m, t 4 mm, 24 x 4 CPS4
  plate_cps8   the same plate, 12 x 2 CPS8
  bar_c3d8     bar 0.2 x 0.02 x 0.012 m, 16 x 3 x 2 C3D8, meshed by Gmsh from
               bar_c3d8.geo (so the test also reads a file Gmsh wrote)
  bar_c3d20    the same bar, 8 x 2 x 1 C3D20 (records continued over two lines);
               bar_c3d20_gmsh.inp is Gmsh's mesh of it (bar_c3d20_gmsh.geo), only
               meshed: the test checks it against bar_c3d20's reference
  bar_c3d10    the same bar, 120 C3D10 (10 x 2 x 1 boxes of 6 tetrahedra), meshed by
               Gmsh from bar_c3d10.geo
  bar_c3d6     the same bar, 192 C3D6 (16 x 3 x 2 boxes of 2 wedges: triangles
               extruded), meshed by Gmsh from bar_c3d6.geo
  bar_c3d15    the same bar, 32 C3D15 (8 x 2 x 1 boxes of 2 wedges), meshed by Gmsh
               from bar_c3d15.geo
  solid_slider_crank_c3d10
               the rod of solid_slider_crank below in C3D10 (its faces in
               triangles, extruded as tetrahedra), meshed by Gmsh from
               solid_slider_crank_c3d10.geo, clamped at BIG_END
  solid_slider_crank
               the connecting rod of models/solid_slider_crank.json, 28 C3D20
               meshed by Gmsh from models/solid_slider_crank.geo (the shipped
               mesh, read as it is), Simeon's steel (E 2e11, nu 0.3, rho 7870),
               clamped at its big-end bore (node set BIG_END)

For each mesh this writes NAME.inp (the mesh; Gmsh's own output for bar_c3d8;
not for a shipped mesh, which it only reads) and NAME_ccx.txt: parameters as
"# key value" lines, then
"support mode omega_rad_s frequency_hz" for support clamped (modes 1-12) and
free (the first 12 elastic modes: 4-15 of a plate, whose 1-3 are its rigid
motions in its plane, 7-18 of a bar).

The CalculiX job adds material, section, boundary and step to the mesh; for
the Gmsh mesh it keeps only the solid elements (Gmsh also writes the ROOT
face's quadrilaterals, which the kanegen reader skips for the same reason).

Usage: tests/fem/ccx/make_solid_reference.py [--ccx ccx] [--gmsh gmsh] [--only NAME ...]
(needs calculix-ccx and gmsh; Debian: apt-get install calculix-ccx gmsh)
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
MODELS_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "models")

MATERIAL = {"E": 2.1e11, "nu": 0.3, "rho": 7850.0}
PLATE = {"L": 0.3, "H": 0.05, "t": 0.004}
BAR = {"L": 0.2, "H": 0.02, "T": 0.012}
MODES = 12

# Meshes Gmsh makes from NAME.geo, with these options besides the .inp format and node sets.
GMSH_SECOND_ORDER = ["-order", "2", "-setnumber", "Mesh.SecondOrderIncomplete", "1"]
# Meshed only, not run: the test reads it and compares it with bar_c3d20's reference (the same mesh).
GMSH_ONLY = {"bar_c3d20_gmsh": GMSH_SECOND_ORDER}

MODELS = {
    "plate_cps4": {"type": "CPS4", "divisions": (24, 4)},
    "plate_cps8": {"type": "CPS8", "divisions": (12, 2)},
    "bar_c3d8": {"type": "C3D8", "gmsh": []},
    "bar_c3d20": {"type": "C3D20", "divisions": (8, 2, 1)},
    "bar_c3d10": {"type": "C3D10", "gmsh": ["-order", "2"]},
    "bar_c3d6": {"type": "C3D6", "gmsh": []},
    "bar_c3d15": {"type": "C3D15", "gmsh": GMSH_SECOND_ORDER},
    "solid_slider_crank_c3d10": {"type": "C3D10", "gmsh": ["-order", "2"], "clamp": "BIG_END",
                                 "material": {"E": 2.0e11, "nu": 0.3, "rho": 7870.0}},
    # A shipped mesh: read from models/, clamped at its own node set, in its model's material.
    "solid_slider_crank": {"type": "C3D20", "shipped": True, "clamp": "BIG_END",
                           "material": {"E": 2.0e11, "nu": 0.3, "rho": 7870.0}},
}

# Natural coordinates of the nodes, CalculiX order (as generator/fem/continuum_element.cpp).
QUAD = [(-1, -1), (1, -1), (1, 1), (-1, 1), (0, -1), (1, 0), (0, 1), (-1, 0)]
HEX = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1),
       (0, -1, -1), (1, 0, -1), (0, 1, -1), (-1, 0, -1), (0, -1, 1), (1, 0, 1), (0, 1, 1), (-1, 0, 1),
       (-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]


def structured_mesh(etype, divisions, sizes):
    """Nodes {grid index: id} on a grid of half-element spacing, and element node-id lists."""
    quadratic = etype in ("CPS8", "C3D20")
    local = QUAD[: 8 if quadratic else 4] if len(divisions) == 2 else HEX[: 20 if quadratic else 8]
    ids, coords, elements = {}, [], []
    for cell in sorted(_cells(divisions)):
        element = []
        for c in local:
            key = tuple(2 * i + 1 + s for i, s in zip(cell, c))  # half-spacing grid index
            if key not in ids:
                ids[key] = len(coords) + 1
                coords.append(tuple(k * size / (2 * n) for k, size, n in zip(key, sizes, divisions)))
            element.append(ids[key])
        elements.append(element)
    return coords, elements


def _cells(divisions):
    if len(divisions) == 2:
        return [(i, j) for i in range(divisions[0]) for j in range(divisions[1])]
    return [(i, j, k) for i in range(divisions[0]) for j in range(divisions[1]) for k in range(divisions[2])]


def write_structured(path, name, model):
    plane = len(model["divisions"]) == 2
    sizes = (PLATE["L"], PLATE["H"]) if plane else (BAR["L"], BAR["H"], BAR["T"])
    coords, elements = structured_mesh(model["type"], model["divisions"], sizes)
    root = sorted(i for i, x in enumerate(coords, start=1) if x[0] == 0.0)
    with open(path, "w") as f:
        f.write(f"** kanegen tests/fem reference mesh {name}, written by tests/fem/ccx/make_solid_reference.py\n")
        f.write("*NODE, NSET=NALL\n")
        for i, x in enumerate(coords, start=1):
            f.write(f"{i}, " + ", ".join(f"{v:.12g}" for v in x) + "\n")
        f.write(f"*ELEMENT, TYPE={model['type']}, ELSET=EBODY\n")
        for i, nodes in enumerate(elements, start=1):
            # At most 16 entries per line in .inp: longer records continue after a trailing comma.
            first, rest = nodes[:10], nodes[10:]
            f.write(f"{i}, " + ", ".join(map(str, first)) + ("," if rest else "") + "\n")
            if rest:
                f.write(", ".join(map(str, rest)) + "\n")
        f.write("*NSET, NSET=ROOT\n")
        for k in range(0, len(root), 8):
            f.write(", ".join(map(str, root[k : k + 8])) + "\n")
        f.write("*ELSET, ELSET=EALL, GENERATE\n")
        f.write(f"1, {len(elements)}, 1\n")


def mesh_for_ccx(path, etype):
    """The mesh's *NODE, *NSET and etype *ELEMENT blocks (element set EBODY); other blocks dropped."""
    out, keep = [], False
    for line in open(path):
        if line.startswith("**"):
            continue
        if line.startswith("*"):
            head = [p.strip().upper() for p in line.split(",")]
            if head[0] == "*ELEMENT":
                keep = f"TYPE={etype}" in head
                line = f"*ELEMENT, TYPE={etype}, ELSET=EBODY\n"
            else:
                keep = head[0] in ("*NODE", "*NSET")
        if keep:
            out.append(line)
    return "".join(out)


def run_ccx(ccx, mesh_text, etype, clamped, material=MATERIAL, clamp="ROOT"):
    plane = etype.startswith("CPS")
    deck = [mesh_text, "*MATERIAL, NAME=STEEL\n*ELASTIC\n",
            f"{material['E']:.12g}, {material['nu']:.12g}\n*DENSITY\n{material['rho']:.12g}\n",
            "*SOLID SECTION, ELSET=EBODY, MATERIAL=STEEL\n"]
    if plane:
        deck.append(f"{PLATE['t']:.12g}\n")
    if clamped:
        deck.append(f"*BOUNDARY\n{clamp}, 1, {2 if plane else 3}\n")
    rigid = 0 if clamped else (3 if plane else 6)  # a free plane body moves rigidly in its plane only
    deck.append(f"*STEP\n*FREQUENCY\n{MODES + rigid}\n*END STEP\n")
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "job.inp"), "w") as f:
            f.write("".join(deck))
        log = subprocess.run([ccx, "job"], cwd=work, capture_output=True, text=True)
        if log.returncode != 0 or "ERROR" in log.stdout:
            sys.exit(f"ccx failed ({etype}, clamped={clamped}):\n{log.stdout}\n{log.stderr}")
        with open(os.path.join(work, "job.dat")) as f:
            dat = f.read()
    block = dat.split("E I G E N V A L U E   O U T P U T", 1)[1]
    rows = re.findall(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", block, re.M)
    freqs = [(int(m), float(rad), float(hz)) for m, _, rad, hz, _ in rows]
    first = rigid + 1
    freqs = [f for f in freqs if first <= f[0] < first + MODES]
    if len(freqs) != MODES:
        sys.exit(f"expected {MODES} eigenvalues from mode {first} ({etype}, clamped={clamped})")
    return freqs


def ccx_version(ccx):
    out = subprocess.run([ccx, "-v"], capture_output=True, text=True).stdout
    match = re.search(r"Version\s+(\S+)", out)
    return match.group(1) if match else "unknown"


def gmsh_mesh(gmsh, name, options):
    subprocess.run([gmsh, "-3", *options, "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1",
                    name + ".geo", "-o", name + ".inp"], cwd=DATA, check=True, capture_output=True)


def write_frequencies(f, name, results):
    """The table of a reference file (support, mode, omega, frequency), also printed as a summary."""
    f.write("# support mode omega_rad_s frequency_hz\n")
    for support, freqs in results.items():
        for mode, rad, hz in freqs:
            f.write(f"{support} {mode} {rad:.7e} {hz:.7e}\n")
    for support, freqs in results.items():
        print(f"{name} {support}: " + ", ".join(f"{rad:.6g}" for _, rad, _ in freqs) + " rad/s")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ccx", default="ccx")
    parser.add_argument("--gmsh", default="gmsh")
    parser.add_argument("--only", nargs="+", metavar="NAME", help="write only these references")
    args = parser.parse_args()
    version = ccx_version(args.ccx)
    for name, options in GMSH_ONLY.items():
        if not args.only or name in args.only:
            gmsh_mesh(args.gmsh, name, options)
    for name, model in MODELS.items():
        if args.only and name not in args.only:
            continue
        inp = os.path.join(MODELS_DIR if model.get("shipped") else DATA, name + ".inp")
        material, clamp = model.get("material", MATERIAL), model.get("clamp", "ROOT")
        if "gmsh" in model:
            gmsh_mesh(args.gmsh, name, model["gmsh"])
        elif not model.get("shipped"):
            write_structured(inp, name, model)
        mesh = mesh_for_ccx(inp, model["type"])
        results = {s: run_ccx(args.ccx, mesh, model["type"], s == "clamped", material, clamp)
                   for s in ("clamped", "free")}
        with open(os.path.join(DATA, name + "_ccx.txt"), "w") as f:
            where = "models/" if model.get("shipped") else ""
            f.write(f"# CalculiX {version} ({model['type']}, *FREQUENCY), mesh {where}{name}.inp"
                    f"{', clamped at ' + clamp if clamp != 'ROOT' else ''}, by tests/fem/ccx/make_solid_reference.py\n")
            f.write(f"# E {material['E']:.12g}\n# nu {material['nu']:.12g}\n# rho {material['rho']:.12g}\n")
            if model["type"].startswith("CPS"):
                f.write(f"# thickness {PLATE['t']:.12g}\n")
            write_frequencies(f, name, results)


if __name__ == "__main__":
    main()
