#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Writes models/chain20.urdf: a 20-link spatial serial chain (or N links with --links N).

The output is deterministic (no randomness, fixed number formatting), so the
committed file is exactly what this script writes:

    python3 scripts/make_chain_urdf.py            # writes models/chain20.urdf
    python3 scripts/make_chain_urdf.py -o FILE    # writes elsewhere
    python3 scripts/make_chain_urdf.py --check    # fails if the file is stale
    python3 scripts/make_chain_urdf.py --links 100 -o chain100.urdf   # robot "chain100"

Every link is a box-like body with its centre of mass off the joint axis and a
full inertia tensor: the principal moments of a solid box, rotated by a
link-dependent rotation (so ixy, ixz, iyz are non-zero), and every other link
also has a rotated inertial frame. The joint axes cycle through z, y, x and -y,
and the joint origins carry small rpy rotations, so the chain is truly spatial.
Joints alternate between continuous and revolute (with limits); the root link
"base" is the ground. The script checks that each inertia is positive definite
and satisfies the triangle inequality before writing.
"""

import argparse
import math
import os
import sys

DEFAULT_LINKS = 20
AXES = ["0 0 1", "0 1 0", "1 0 0", "0 -1 0"]


def fmt(x):
    """Fixed, platform-independent number formatting (12 significant digits)."""
    if abs(x) < 1e-15:
        return "0"
    return "%.12g" % x


def rot_rpy(roll, pitch, yaw):
    """URDF rotation: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]


def rotate_inertia(r, principal):
    """R diag(principal) R^T."""
    return [[sum(r[i][k] * principal[k] * r[j][k] for k in range(3)) for j in range(3)] for i in range(3)]


def eig_sym3(a):
    """Eigenvalues of a symmetric 3x3 matrix (closed form), ascending."""
    p1 = a[0][1] ** 2 + a[0][2] ** 2 + a[1][2] ** 2
    q = (a[0][0] + a[1][1] + a[2][2]) / 3.0
    p2 = sum((a[i][i] - q) ** 2 for i in range(3)) + 2.0 * p1
    p = math.sqrt(p2 / 6.0)
    if p == 0.0:
        return [q, q, q]
    b = [[(a[i][j] - (q if i == j else 0.0)) / p for j in range(3)] for i in range(3)]
    det = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
           b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]))
    phi = math.acos(max(-1.0, min(1.0, det / 2.0))) / 3.0
    e1 = q + 2.0 * p * math.cos(phi)
    e3 = q + 2.0 * p * math.cos(phi + 2.0 * math.pi / 3.0)
    return sorted([e1, 3.0 * q - e1 - e3, e3])


def link_data(i):
    """Parameters of moving link i (1..n_links), from smooth deterministic formulas."""
    length = 0.12 + 0.03 * ((i * 7) % 5)  # 0.12 .. 0.24 m
    width = 0.05 + 0.01 * (i % 3)
    depth = 0.035 + 0.01 * ((i + 1) % 4)
    # The mass falls along the first 20 links and repeats that pattern further
    # out, so a chain of any length stays positive (and chain20 is unchanged).
    mass = 1.6 - 0.05 * ((i - 1) % 20 + 1) + 0.1 * math.sin(1.3 * i)
    com = [0.012 * math.sin(0.9 * i), 0.01 * math.cos(1.7 * i), 0.5 * length + 0.01 * math.sin(2.3 * i)]
    # principal moments of a solid box (width x depth x length), about its centre
    principal = [
        mass / 12.0 * (depth**2 + length**2),
        mass / 12.0 * (width**2 + length**2),
        mass / 12.0 * (width**2 + depth**2),
    ]
    # the tensor is written in axes rotated by `tilt` from the inertial frame
    tilt = rot_rpy(0.4 * math.sin(1.1 * i), 0.3 * math.cos(0.7 * i), 0.5 * math.sin(0.4 * i + 1.0))
    inertia = rotate_inertia(tilt, principal)
    inertial_rpy = [0.2 * math.sin(0.8 * i), -0.15 * math.cos(1.9 * i), 0.3 * math.sin(0.5 * i)] if i % 2 else [0, 0, 0]
    return length, mass, com, inertia, inertial_rpy


def joint_data(i, parent_length):
    """Joint i connects link i-1 to link i; it sits at the far end of link i-1."""
    xyz = [0.01 * math.cos(1.2 * i), -0.008 * math.sin(0.6 * i), parent_length]
    rpy = [0.35 * math.sin(1.5 * i), 0.25 * math.cos(0.9 * i), 0.45 * math.sin(0.7 * i + 0.5)]
    axis = AXES[(i - 1) % len(AXES)]
    kind = "continuous" if i % 2 else "revolute"
    return xyz, rpy, axis, kind


def inertial_xml(mass, com, rpy, inertia, indent):
    a = inertia
    ev = eig_sym3(a)
    if ev[0] <= 0.0:
        raise ValueError("inertia not positive definite: %r" % (ev,))
    if ev[0] + ev[1] < ev[2] * (1.0 + 1e-9):
        raise ValueError("inertia violates the triangle inequality: %r" % (ev,))
    pad = " " * indent
    return "\n".join([
        pad + "<inertial>",
        pad + '  <origin xyz="%s" rpy="%s"/>' % (" ".join(fmt(c) for c in com), " ".join(fmt(c) for c in rpy)),
        pad + '  <mass value="%s"/>' % fmt(mass),
        pad + '  <inertia ixx="%s" ixy="%s" ixz="%s" iyy="%s" iyz="%s" izz="%s"/>' %
        (fmt(a[0][0]), fmt(a[0][1]), fmt(a[0][2]), fmt(a[1][1]), fmt(a[1][2]), fmt(a[2][2])),
        pad + "</inertial>",
    ])


def make_urdf(n_links):
    name = "chain%d" % n_links
    out = []
    out.append('<?xml version="1.0"?>')
    out.append("<!-- Generated by scripts/make_chain_urdf.py: do not edit, rerun the script. -->")
    out.append("<!-- %s: a %d-link spatial serial chain; the root link \"base\" is the ground. -->" % (name, n_links))
    out.append('<robot name="%s">' % name)
    out.append("  <!-- Read by MuJoCo's URDF importer only (urdfdom ignores it): one body per link, the inertials")
    out.append("       exactly as written. -->")
    out.append("  <mujoco>")
    out.append('    <compiler fusestatic="false" discardvisual="true" inertiafromgeom="false" balanceinertia="false"')
    out.append('              boundmass="0" boundinertia="0"/>')
    out.append("  </mujoco>")
    out.append("")
    out.append('  <link name="base">')
    out.append(inertial_xml(3.0, [0, 0, 0.05], [0, 0, 0], [[0.02, 0, 0], [0, 0.02, 0], [0, 0, 0.03]], 4))
    out.append("  </link>")
    lengths = {0: 0.1}
    for i in range(1, n_links + 1):
        length, mass, com, inertia, irpy = link_data(i)
        lengths[i] = length
        out.append("")
        out.append('  <link name="link%d">' % i)
        out.append(inertial_xml(mass, com, irpy, inertia, 4))
        out.append("  </link>")
    for i in range(1, n_links + 1):
        xyz, rpy, axis, kind = joint_data(i, lengths[i - 1])
        parent = "base" if i == 1 else "link%d" % (i - 1)
        out.append("")
        out.append('  <joint name="joint%d" type="%s">' % (i, kind))
        out.append('    <parent link="%s"/>' % parent)
        out.append('    <child link="link%d"/>' % i)
        out.append('    <origin xyz="%s" rpy="%s"/>' % (" ".join(fmt(c) for c in xyz), " ".join(fmt(c) for c in rpy)))
        out.append('    <axis xyz="%s"/>' % axis)
        if kind == "revolute":
            out.append('    <limit lower="-3" upper="3" effort="100" velocity="5"/>')
        out.append("  </joint>")
    out.append("</robot>")
    return "\n".join(out) + "\n"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.join(here, os.pardir, "models", "chain20.urdf")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", help="output file (default: models/chain20.urdf; required with --links other than 20)")
    parser.add_argument("--links", type=int, default=DEFAULT_LINKS,
                        help="number of moving links, at least 1 (default: %d); the robot is named chain<N>" % DEFAULT_LINKS)
    parser.add_argument("--check", action="store_true", help="exit 1 if the output file differs from what would be written")
    args = parser.parse_args()
    if args.links < 1:
        parser.error("--links must be at least 1, not %d" % args.links)
    if args.output is None:
        if args.links != DEFAULT_LINKS:
            parser.error("--links %d writes chain%d: give the output file with -o (models/chain20.urdf is the "
                         "20-link chain)" % (args.links, args.links))
        args.output = default_out
    text = make_urdf(args.links)
    if args.check:
        try:
            with open(args.output, encoding="utf-8") as f:
                current = f.read()
        except OSError:
            current = None
        if current != text:
            print("%s is stale: rerun scripts/make_chain_urdf.py" % args.output, file=sys.stderr)
            return 1
        return 0
    with open(args.output, "w", encoding="utf-8") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
