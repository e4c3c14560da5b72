#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""kanegen animate --format vtk, read back with VTK's own XML reader.

The frames' geometry comes from the numeric path's poses; the reference is
the generated kernels' outputs, the columns `kanegen simulate` wrote for the
same rows: frame origins against point outputs at those origins, the nodes
of a flexible link against its origin, its x axis and its node
displacement outputs (at scale 1 and magnified), and a rigid body's box
against the closed form of a box's principal moments.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError:
    print("SKIP: python3-vtk9 is not installed (scripts/install-deps.sh installs it)")
    sys.exit(77)
import numpy as np

TOL = 1e-9
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def run(*args):
    subprocess.run([str(a) for a in args], check=True)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    return header, [[float(x) for x in r] for r in rows[1:] if r]


def frames_of(pvd):
    root = ET.parse(pvd).getroot()
    base = os.path.dirname(pvd)
    return [(float(d.get("timestep")), os.path.join(base, d.get("file"))) for d in root.iter("DataSet")]


def read_vtu(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    data = grid.GetPointData()
    cells = [grid.GetCellType(i) for i in range(grid.GetNumberOfCells())]
    return {
        "points": vtk_to_numpy(grid.GetPoints().GetData()),
        "body": vtk_to_numpy(data.GetArray("body")),
        "kind": vtk_to_numpy(data.GetArray("kind")),
        "displacement": vtk_to_numpy(data.GetArray("displacement")),
        "cells": cells,
        "cell_body": vtk_to_numpy(grid.GetCellData().GetArray("body")),
    }


def column(header, row, name):
    return row[header.index(name)]


def point_output(header, row, name):
    return np.array([column(header, row, name + "." + a) for a in "xyz"])


def box_moments(corners):
    """Principal moments of a solid box of mass m from its eight corners (VTK order)."""
    a = np.linalg.norm(corners[1] - corners[0])
    b = np.linalg.norm(corners[3] - corners[0])
    c = np.linalg.norm(corners[4] - corners[0])
    return sorted([(b * b + c * c) / 12, (a * a + c * c) / 12, (a * a + b * b) / 12])


def check_arm(kanegen, model, work):
    csv_path = os.path.join(work, "arm.csv")
    run(kanegen, "simulate", model, "--t-end", "0.3", "-o", csv_path, "--quiet")
    header, rows = read_csv(csv_path)
    times = {row[0]: row for row in rows}
    for scale in (1.0, 10.0):
        out = os.path.join(work, "arm_vtk_%g" % scale)
        run(kanegen, "animate", csv_path, model, "-o", out, "--frames", "3", "--scale", scale, "--quiet")
        frames = frames_of(os.path.join(out, "animate_arm.pvd"))
        check(len(frames) == 3, "three frames, got %d" % len(frames))
        check(frames[0][0] == rows[0][0] and frames[-1][0] == rows[-1][0], "the first and the last row are frames")
        for t, path in frames:
            check_arm_frame(read_vtu(path), header, times[t], scale, "t=%g scale %g" % (t, scale))


def check_arm_frame(g, header, row, scale, where):
    pts, body, kind = g["points"], g["body"], g["kind"]
    # Bodies in model order: hub 0, link1 1, motor 2, link2 3.
    for b, name in ((0, "hub_origin"), (2, "motor_origin"), (3, "link2_origin")):
        origin = pts[(body == b) & (kind == 0)]
        check(len(origin) == 1, "%s: one frame origin of body %d" % (where, b))
        err = np.abs(origin[0] - point_output(header, row, name)).max()
        check(err < TOL, "%s: %s off by %.3g" % (where, name, err))
    o2 = point_output(header, row, "link2_origin")
    ex = point_output(header, row, "link2_x") - o2
    ey = np.array([-ex[1], ex[0], 0.0])  # link2 turns about z
    nodes = pts[(body == 3) & (kind == 2)]
    displacement = g["displacement"][(body == 3) & (kind == 2)]
    check(len(nodes) == 5, "%s: link2 has 5 nodes, got %d" % (where, len(nodes)))
    for node, name in ((4, "tip2"), (2, "mid2")):
        u = [column(header, row, name + "." + a) for a in "xy"]
        expected = o2 + ex * (0.25 * node + scale * u[0]) + ey * (scale * u[1])
        err = np.abs(nodes[node] - expected).max()
        check(err < TOL, "%s: link2 node %d off by %.3g" % (where, node, err))
        err = np.abs(displacement[node] - (ex * u[0] + ey * u[1])).max()
        check(err < TOL, "%s: link2 node %d displacement off by %.3g" % (where, node, err))
    # The hub's box: mass 1.5 and the principal moments of its inertia, about its centre of mass.
    corners = pts[(body == 0) & (kind == 1)]
    check(len(corners) == 8, "%s: the hub's box has 8 corners" % where)
    inertia = np.array([[0.004, 0.0005, 0], [0.0005, 0.006, 0], [0, 0, 0.008]])
    moments = np.array(box_moments(corners)) * 1.5
    err = np.abs(moments - np.sort(np.linalg.eigvalsh(inertia))).max()
    check(err < TOL, "%s: the hub box's moments off by %.3g" % (where, err))
    ho = point_output(header, row, "hub_origin")
    hx = point_output(header, row, "hub_x") - ho
    hy = np.array([-hx[1], hx[0], 0.0])
    err = np.abs(corners.mean(axis=0) - (ho + 0.02 * hx + 0.01 * hy)).max()
    check(err < TOL, "%s: the hub box's centre off the centre of mass by %.3g" % (where, err))
    check(12 in g["cells"] and 4 in g["cells"], "%s: a hexahedron (box) and a polyline (beam)" % where)


def check_free_body(kanegen, model, work):
    """A box on a free joint and an arm on a spherical one (quaternions): frame origins and box centres."""
    csv_path = os.path.join(work, "free_body.csv")
    run(kanegen, "simulate", model, "--t-end", "0.5", "-o", csv_path, "--quiet", "--u0", "base_wx=3",
        "--u0", "base_wy=-2", "--u0", "base_z_dot=1", "--u0", "wrist_wz=5", "--u0", "wrist_wx=1")
    header, rows = read_csv(csv_path)
    times = {row[0]: row for row in rows}
    out = os.path.join(work, "free_body_vtk")
    run(kanegen, "animate", csv_path, model, "-o", out, "--frames", "3", "--quiet")
    frames = frames_of(os.path.join(out, "free_body.pvd"))
    check(len(frames) == 3, "free body: three frames, got %d" % len(frames))
    for t, path in frames:
        g = read_vtu(path)
        pts, body, kind = g["points"], g["body"], g["kind"]
        for b, name in ((0, "box"), (1, "arm")):
            where = "free body t=%g %s" % (t, name)
            origin = pts[(body == b) & (kind == 0)]
            check(len(origin) == 1, "%s: one frame origin" % where)
            err = np.abs(origin[0] - point_output(header, times[t], name + "_origin")).max()
            check(err < TOL, "%s: origin off by %.3g" % (where, err))
            corners = pts[(body == b) & (kind == 1)]
            check(len(corners) == 8, "%s: a box of 8 corners" % where)
            err = np.abs(corners.mean(axis=0) - point_output(header, times[t], name + "_com")).max()
            check(err < TOL, "%s: the box's centre off the centre of mass by %.3g" % (where, err))


def check_mesh(kanegen, model, work):
    csv_path = os.path.join(work, "plate.csv")
    run(kanegen, "simulate", model, "--t-end", "0.02", "-o", csv_path, "--quiet")
    out = os.path.join(work, "plate_vtk")
    run(kanegen, "animate", csv_path, model, "-o", out, "--frames", "2", "--quiet")
    frames = frames_of(os.path.join(out, "plate_hub.pvd"))
    with open(model.replace(".json", ".inp")) as f:
        text = f.read()
    elements = text.split("type=CPS4")[1].split("*")[0].strip().splitlines()[1:]
    for _, path in frames:
        g = read_vtu(path)
        quads = [c for c in g["cells"] if c == 9]
        check(len(quads) == len(elements), "plate: %d quads for %d CPS4 elements" % (len(quads), len(elements)))
        check(np.isfinite(g["points"]).all() and np.isfinite(g["displacement"]).all(), "plate: finite points")


def check_refusals(kanegen, source, work):
    """A CSV of another model, and a row cut short: an error naming the file and the fix, no files."""
    arm_csv = os.path.join(work, "arm.csv")
    other = os.path.join(source, "models/double_pendulum.json")  # its coordinates are also the arm's first two
    out = os.path.join(work, "refused")
    r = subprocess.run([kanegen, "animate", arm_csv, other, "-o", out, "--quiet"], capture_output=True, text=True)
    check(r.returncode == 1 and "column 4 is 'link1.n1.u'" in r.stderr and "give the CSV of a run of this model"
          in r.stderr, "a CSV of another model is refused: %r" % r.stderr)
    cut = os.path.join(work, "cut.csv")
    with open(arm_csv) as f, open(cut, "w") as g:
        lines = f.read().splitlines()
        g.write("\n".join(lines[:3] + [lines[3][:40]]) + "\n")
    model = os.path.join(source, "tests/data/models/animate_arm.json")
    r = subprocess.run([kanegen, "animate", cut, model, "-o", out, "--quiet"], capture_output=True, text=True)
    check(r.returncode == 1 and "cut.csv: line 4:" in r.stderr, "a row cut short is refused: %r" % r.stderr)
    check(not os.path.exists(out) or not os.listdir(out), "nothing written for refused input")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--kanegen", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)  # a stale frame would pass for a new one
    os.makedirs(a.work)
    check_arm(a.kanegen, os.path.join(a.source, "tests/data/models/animate_arm.json"), a.work)
    check_refusals(a.kanegen, a.source, a.work)
    check_free_body(a.kanegen, os.path.join(a.source, "tests/consistency/data/free_body.json"), a.work)
    check_mesh(a.kanegen, os.path.join(a.source, "models/plate_hub.json"), a.work)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
