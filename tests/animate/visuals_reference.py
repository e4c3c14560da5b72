# SPDX-License-Identifier: GPL-2.0-or-later
"""Where the <visual> shapes of tests/data/models/animate_visuals.urdf are, computed by hand.

From the URDF's own numbers, with rotation matrices written out here: the
arm turns by j1 about z at the origin; its box (0.4 x 0.1 x 0.05) sits at
(0.2, 0, 0), rolled 0.3 rad about x; its cylinder (r 0.03, length 0.2) at
(0.4, 0, 0), turned pi/2 about y, so its axis is the arm's x. The hand turns
by j2 about y at the arm's (0.4, 0, 0); its sphere (r 0.05) is at (0.1,
0.02, 0) of the hand; its mesh is drawn as the box of the hand's mass (0.5)
and diagonal inertia (0.0004, 0.0009, 0.0011) about its centre of mass
(0.05, 0, 0): sides sqrt(6 (I_j + I_k - I_i) / m).

Used by check_vtk.py (VTK's reader, to 1e-9) and check_html.py (the page's
float32 world positions). Shapes come as (kind, points), points world.
"""
import math

MODEL = "tests/data/models/animate_visuals.urdf"
# t, j1, j2 (the CSV the tests write: the coordinates only matter here)
ROWS = [(0.0, 0.3, -0.4), (0.1, 0.7, 0.5), (0.2, -1.1, 1.2)]
SIDES, RINGS = 24, 11  # generator/animate/shapes.hpp: a cylinder's rims, a sphere's rings
CYLINDER_POINTS, SPHERE_POINTS = 2 * SIDES, 2 + SIDES * RINGS
# VTK's hexahedron order: the bottom face (z -) counter-clockwise, then the top.
SIGNS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]


def csv_text():
    lines = ["t,j1,j2,j1_dot,j2_dot"] + ["%r,%r,%r,0,0" % row for row in ROWS]
    return "\n".join(lines) + "\n"


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def mv(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def mm(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def norm(a):
    return math.sqrt(sum(x * x for x in a))


def mean(points):
    return [sum(p[i] for p in points) / len(points) for i in range(3)]


def expected(q1, q2):
    arm = rz(q1)
    hand, hand_origin = mm(arm, ry(q2)), mv(arm, [0.4, 0, 0])
    box = [mv(arm, add([0.2, 0, 0], mv(rx(0.3), [0.2 * a, 0.05 * b, 0.025 * c]))) for a, b, c in SIGNS]
    m, ixx, iyy, izz = 0.5, 0.0004, 0.0009, 0.0011
    half = [0.5 * math.sqrt(6 * (iyy + izz - ixx) / m), 0.5 * math.sqrt(6 * (ixx + izz - iyy) / m),
            0.5 * math.sqrt(6 * (ixx + iyy - izz) / m)]
    inertia_box = [add(hand_origin, mv(hand, [0.05 + a * half[0], b * half[1], c * half[2]])) for a, b, c in SIGNS]
    return {
        "box": box,
        "cylinder": (mv(arm, [0.4, 0, 0]), mv(mm(arm, ry(math.pi / 2)), [0, 0, 1]), 0.03, 0.2),
        "sphere": (add(hand_origin, mv(hand, [0.1, 0.02, 0])), 0.05),
        "inertia_box": inertia_box,
    }


def compare(arm, hand, q1, q2, tol, check):
    """arm, hand: their shapes, [(kind, points)]; check(ok, what) records a failure. The largest error."""
    e = expected(q1, q2)
    worst = 0.0
    where = "q = (%g, %g)" % (q1, q2)

    def near(err, what):
        nonlocal worst
        worst = max(worst, err)
        check(err < tol, "%s: %s off by %.3g" % (where, what, err))

    kinds = [k for k, _ in arm] + [k for k, _ in hand]
    check(kinds == ["box", "cylinder", "sphere", "inertia"], "%s: the shapes drawn: %s" % (where, kinds))
    if kinds != ["box", "cylinder", "sphere", "inertia"]:
        return worst
    (_, box), (_, cylinder), (_, sphere), (_, inertia) = arm[0], arm[1], hand[0], hand[1]
    check(len(box) == 8 and len(cylinder) == CYLINDER_POINTS and len(sphere) == SPHERE_POINTS and
          len(inertia) == 8, "%s: point counts %d %d %d %d" % (where, len(box), len(cylinder), len(sphere),
                                                               len(inertia)))
    for k, (p, q) in enumerate(zip(box, e["box"])):
        near(norm(sub(p, q)), "the box's corner %d" % k)
    centre, axis, r, length = e["cylinder"]
    near(norm(sub(mean(cylinder), centre)), "the cylinder's centre")
    ends = sub(mean(cylinder[SIDES:]), mean(cylinder[:SIDES]))
    near(norm(sub(ends, [length * a for a in axis])), "the cylinder's axis times its length")
    for p in cylinder:
        d = sub(p, centre)
        along = sum(x * a for x, a in zip(d, axis))
        near(abs(norm(sub(d, [along * a for a in axis])) - r), "a rim point's distance from the axis")
        near(abs(abs(along) - length / 2), "a rim point's distance from the middle, along the axis")
    centre, r = e["sphere"]
    near(norm(sub(mean(sphere), centre)), "the sphere's centre")
    for p in sphere:
        near(abs(norm(sub(p, centre)) - r), "a sphere point's distance from the centre")
    for q in e["inertia_box"]:  # the principal axes' signs are the solver's: the corners as a set
        near(min(norm(sub(p, q)) for p in inertia), "a corner of the hand's inertia box")
    return worst
