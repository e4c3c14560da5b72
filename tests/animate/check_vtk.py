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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

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
        "cell_points": [[grid.GetCell(i).GetPointId(k) for k in range(grid.GetCell(i).GetNumberOfPoints())]
                        for i in range(grid.GetNumberOfCells())],
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


def check_tet_mesh(kanegen, model, work):
    """A C3D10 bar (tests/data/models/tip_bar_c3d10.json): one VTK_QUADRATIC_TETRA per element, each with
    VTK's orientation (corners 0-1-2 turn right-handed towards corner 3) and its mid-edge points halfway
    along VTK's edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3 (to 1e-6 m: the steel bar bends by microns)."""
    csv_path = os.path.join(work, "tet.csv")
    run(kanegen, "simulate", model, "--t-end", "0.02", "-o", csv_path, "--quiet")
    out = os.path.join(work, "tet_vtk")
    run(kanegen, "animate", csv_path, model, "-o", out, "--frames", "2", "--quiet")
    with open(model.replace(".json", ".inp")) as f:
        text = f.read()
    elements = text.split("type=C3D10")[1].split("*")[0].strip().splitlines()[1:]
    for _, path in frames_of(os.path.join(out, "tip_bar_c3d10.pvd")):
        g = read_vtu(path)
        tets = [p for c, p in zip(g["cells"], g["cell_points"]) if c == 24]
        check(len(tets) == len(elements), "tet bar: %d quadratic tetra for %d C3D10" % (len(tets), len(elements)))
        x = g["points"]
        for p in tets:
            volume = np.linalg.det(np.array([x[p[1]] - x[p[0]], x[p[2]] - x[p[0]], x[p[3]] - x[p[0]]]))
            check(volume > 0, "tet bar: a cell of VTK volume %.3g" % volume)
            for k, (a, b) in enumerate([(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]):
                err = np.abs(x[p[4 + k]] - (x[p[a]] + x[p[b]]) / 2).max()
                check(err < 1e-6, "tet bar: mid-edge point %d off by %.3g" % (4 + k, err))


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


def check_visuals(kanegen, source, work):
    """URDF <visual> shapes: box, cylinder, sphere and a mesh's inertia box, against visuals_reference.py."""
    import visuals_reference as ref
    model = os.path.join(source, ref.MODEL)
    csv_path = os.path.join(work, "visuals.csv")
    with open(csv_path, "w") as f:
        f.write(ref.csv_text())
    out = os.path.join(work, "visuals_vtk")
    r = subprocess.run([kanegen, "animate", csv_path, model, "-o", out, "--quiet"], capture_output=True, text=True)
    check(r.returncode == 0, "animate of animate_visuals.urdf: %r" % r.stderr)
    check("link 'hand': a <visual> mesh ('package://hand/</script>hand.stl') is drawn as the box of the link's "
          "mass and inertia" in r.stderr, "the mesh is said to be drawn as the inertia box: %r" % r.stderr)
    frames = frames_of(os.path.join(out, "animate_visuals.pvd"))
    check(len(frames) == 3, "3 frames, got %d" % len(frames))
    worst = 0.0
    for (t, path), (_, q1, q2) in zip(frames, ref.ROWS):
        g = read_vtu(path)
        shape = [g["points"][(g["body"] == b) & (g["kind"] == 1)].tolist() for b in (0, 1)]
        arm = [("box", shape[0][:8]), ("cylinder", shape[0][8:])]
        hand = [("sphere", shape[1][:ref.SPHERE_POINTS]), ("inertia", shape[1][ref.SPHERE_POINTS:])]
        worst = max(worst, ref.compare(arm, hand, q1, q2, TOL, check))
        for b, expected in ((0, {12: 1, 9: ref.SIDES, 7: 2}), (1, {12: 1, 9: ref.SIDES * (ref.RINGS - 1),
                                                                   5: 2 * ref.SIDES})):
            types = [c for c, body in zip(g["cells"], g["cell_body"]) if body == b and c != 1]
            counts = {c: types.count(c) for c in set(types)}
            check(counts == expected, "t=%g: body %d's shape cells %s, expected %s" % (t, b, counts, expected))
    print("visuals: shapes at most %.3g m off the hand-computed positions (tolerance %g m)" % (worst, TOL))


def same_files(a, b):
    """The names of the files in a and b, and whether each is the same bytes in both."""
    names = sorted(os.listdir(a))
    if names != sorted(os.listdir(b)):
        return False
    for name in names:
        with open(os.path.join(a, name), "rb") as f, open(os.path.join(b, name), "rb") as g:
            if f.read() != g.read():
                return False
    return True


def check_simulate_animate(kanegen, source, work):
    """simulate --animate DIR: the series kanegen animate writes of the same CSV, with the run's --set values."""
    arm = os.path.join(source, "tests/data/models/animate_arm.json")
    csv_path, out = os.path.join(work, "sim_arm.csv"), os.path.join(work, "sim_arm_vtk")
    run(kanegen, "simulate", arm, "--t-end", "0.3", "-o", csv_path, "--quiet", "--animate", out,
        "--animate-format", "vtk", "--animate-frames", "3", "--animate-scale", "10")
    alone = os.path.join(work, "sim_arm_alone")
    run(kanegen, "animate", csv_path, arm, "-o", alone, "--frames", "3", "--scale", "10", "--quiet")
    check(same_files(out, alone), "simulate --animate writes what animate writes of its CSV: %s, %s" %
          (sorted(os.listdir(out)), sorted(os.listdir(alone))))
    # double_pendulum with l1 = 2: link2's origin (the elbow) is 2 m from the shoulder at every frame, so
    # the --set value reached the animation too (at the default l1 = 1 it would be 1 m). Without -o: the
    # CSV still goes to stdout, and no temporary file stays in DIR.
    pendulum = os.path.join(source, "models/double_pendulum.json")
    out = os.path.join(work, "sim_pendulum_vtk")
    r = subprocess.run([kanegen, "simulate", pendulum, "--t-end", "0.5", "--set", "l1=2", "--quiet", "--animate",
                        out, "--animate-format", "vtk", "--animate-frames", "4"], capture_output=True, text=True)
    check(r.returncode == 0 and r.stdout.startswith("t,shoulder,elbow,"), "the CSV on stdout: %r" % r.stderr)
    check(sorted(os.listdir(out)) == ["double_pendulum.pvd"] + ["double_pendulum_%05d.vtu" % k for k in range(4)],
          "simulate --animate without -o: the series and nothing else in DIR: %s" % os.listdir(out))
    rows = [[float(x) for x in line.split(",")] for line in r.stdout.splitlines()[1:] if line]
    frames = frames_of(os.path.join(out, "double_pendulum.pvd"))
    check(len(frames) == 4 and frames[0][0] == rows[0][0] and frames[-1][0] == rows[-1][0],
          "4 frames, the first and the last row among them: %s" % [t for t, _ in frames])
    for t, path in frames:
        g = read_vtu(path)
        elbow = g["points"][(g["body"] == 1) & (g["kind"] == 0)]
        q1 = next(row[1] for row in rows if row[0] == t)
        expected = np.array([2 * math.cos(q1), 0.0, -2 * math.sin(q1)])  # about y: x' = (cos, 0, -sin)
        err = np.abs(elbow[0] - expected).max() if len(elbow) == 1 else float("inf")
        check(err < TOL, "simulate --set l1=2 --animate: t=%g: the elbow off by %.3g" % (t, err))
    # Refused before anything is built: --animate-* without --animate, --animate onto a file.
    r = subprocess.run([kanegen, "simulate", pendulum, "--t-end", "0.1", "--animate-frames", "3"],
                       capture_output=True, text=True)
    check(r.returncode != 0 and "--animate-frames requires --animate" in r.stderr, "needs --animate: %r" % r.stderr)
    r = subprocess.run([kanegen, "simulate", pendulum, "--t-end", "0.1", "--animate", csv_path],
                       capture_output=True, text=True)
    check(r.returncode != 0 and csv_path in r.stderr and "kanegen: generating" not in r.stderr,
          "--animate onto a file is refused before the build: %r" % r.stderr)


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
    check_tet_mesh(a.kanegen, os.path.join(a.source, "tests/data/models/tip_bar_c3d10.json"), a.work)
    check_simulate_animate(a.kanegen, a.source, a.work)
    check_visuals(a.kanegen, a.source, a.work)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
