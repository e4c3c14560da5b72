#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Writes models/nfourbar<N>.json: the N four-bar of the IFToMM multibody
benchmark library (problem A02) with N couplers.

    python3 scripts/make_nfourbar.py                # N = 40: models/nfourbar40.json
    python3 scripts/make_nfourbar.py -n 2 -o FILE   # another size, elsewhere
    python3 scripts/make_nfourbar.py --check        # fails if models/nfourbar40.json is stale

The benchmark's original size is N = 40 over 20 s: 2N + 1 = 81 links and 2N =
80 loop equations (one degree of freedom). N + 1 cranks of length l and mass m
are hinged to the ground at x = 0, l, ..., N l; at t = 0 they stand vertical,
and N couplers join their tops. The tree: every crank on its own ground
revolute (absolute angle, pi/2 at t = 0, -1 rad/s: the top of the first crank
moves at 1 m/s along x), coupler k on the tip of crank k-1 (angle relative to
it, -pi/2, +1 rad/s); loop Lk closes coupler k's far end on the tip of crank
k. Whenever the cranks lie along the ground line all links are collinear and
the loop equations lose rank N, which is the point of the benchmark.

The physical motion is the 1-dof parallelogram: with theta the common crank
angle, ((N + 1)/3 + N) m l^2 theta'' = -g m l ((N + 1)/2 + N) cos(theta).
The output is deterministic, so the committed file is exactly what this
script writes (models/nfourbar2.json is written by hand and differs in its
description only).
"""

import argparse
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def body(name):
    return {
        "name": name,
        "mass": "m",
        "com": ["l/2", 0, 0],
        "inertia": {"ixx": 0, "iyy": "m*l^2/12", "izz": "m*l^2/12"},
    }


def crank_joint(k):
    joint = {
        "name": f"crank{k}_angle",
        "type": "continuous",
        "parent": "ground",
        "child": f"crank{k}",
        "axis": [0, 0, 1],
        "initial": {"q": math.pi / 2, "u": -1.0},
    }
    if k > 0:
        joint["origin"] = {"xyz": [f"{k}*l" if k > 1 else "l", 0, 0]}
    if k == 0:
        joint["independent"] = True
    return joint


def coupler_joint(k):
    return {
        "name": f"coupler{k}_angle",
        "type": "continuous",
        "parent": f"crank{k - 1}",
        "child": f"coupler{k}",
        "origin": {"xyz": ["l", 0, 0]},
        "axis": [0, 0, 1],
        "initial": {"q": -math.pi / 2, "u": 1.0},
    }


def loop(k):
    return {
        "name": f"L{k}",
        "type": "revolute",
        "planar": True,
        "body": f"coupler{k}",
        "point": ["l", 0, 0],
        "body2": f"crank{k}",
        "point2": ["l", 0, 0],
        "axis": [0, 0, 1],
    }


def model(n):
    inertia = (n + 1) / 3 + n
    gravity_term = 9.81 * ((n + 1) / 2 + n)
    return {
        "$schema": "schema/kanegen-model.schema.json",
        "format": "kanegen-model",
        "version": 1,
        "name": f"nfourbar{n}",
        "description": (
            f"The N four-bar mechanism of the IFToMM multibody benchmark library (problem A02; "
            f"M. Gonzalez, D. Dopico, U. Lugris, J. Cuadrado, Multibody System Dynamics 16 (2006) "
            f"179-190) with N = {n}: {2 * n + 1} links of 1 m and 1 kg (izz = 1/12 kg m^2 about the "
            f"centre), {n + 1} cranks hinged to the ground 1 m apart and {n} couplers joining their "
            f"tops, gravity 9.81 m/s^2 along -y; at t = 0 the cranks stand vertical and the top of the "
            f"first moves at 1 m/s along x. {2 * n} loop equations, 1 degree of freedom; the loop "
            f"equations lose rank {n} whenever the cranks lie along the ground line. Exact motion: "
            f"the parallelogram, {inertia:g} theta'' = -{gravity_term:g} cos(theta) for the common "
            f"crank angle theta. The benchmark runs 20 s. Written by scripts/make_nfourbar.py."
        ),
        "parameters": {"l": 1.0, "m": 1.0},
        "gravity": [0, -9.81, 0],
        "bodies": [body(f"crank{k}") for k in range(n + 1)] + [body(f"coupler{k}") for k in range(1, n + 1)],
        "joints": [crank_joint(k) for k in range(n + 1)] + [coupler_joint(k) for k in range(1, n + 1)],
        "loops": [loop(k) for k in range(1, n + 1)],
        "outputs": [{"name": "B0", "type": "point", "body": "crank0", "point": ["l", 0, 0]}],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-n", type=int, default=40, help="number of couplers (default 40)")
    parser.add_argument("-o", "--output", help="output file (default models/nfourbar<N>.json)")
    parser.add_argument("--check", action="store_true", help="fail if the output file differs")
    args = parser.parse_args()
    if args.n < 1:
        parser.error("-n must be at least 1")
    path = args.output or os.path.join(ROOT, "models", f"nfourbar{args.n}.json")
    text = json.dumps(model(args.n), indent=2) + "\n"
    if args.check:
        try:
            with open(path) as f:
                current = f.read()
        except OSError as e:
            sys.exit(f"{path}: {e.strerror}; write it with {sys.argv[0]}")
        if current != text:
            sys.exit(f"{path} is stale: rewrite it with {sys.argv[0]}")
        return
    with open(path, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
