#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""SymPy's Kane's method on the same spatial chain as scripts/make_chain_urdf.py,
the peer for kanegen's generation time in bench/scaling.py.

    bench/sympy_chain.py N        # prints {"links": N, "seconds": ..., "check": ...}

It builds the chain from make_chain_urdf.py's own link and joint data (joint
frames turned by URDF rpy, R = Rz Ry Rx; full inertia tensors in rotated
inertial frames; gravity -9.81 along z), forms the equations with
sympy.physics.mechanics.KanesMethod (kanes_equations) and times that step
alone: SymPy then holds M and f as expressions, about what kanegen has before
it optimizes and prints C++. "mass" and "forcing" are M and f evaluated at
the check state q_i = 0.3 sin(i), u_i = 0.5 cos(i) (i = 1..N; row-major M),
so that bench/scaling.py can check that SymPy's model is kanegen's.
"""
import json
import math
import os
import sys
import time

import sympy as sp
from sympy.physics import mechanics as me

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "scripts"))
import make_chain_urdf as chain  # noqa: E402


def rpy_matrix(rpy):
    return sp.Matrix(chain.rot_rpy(*rpy))


def build(n_links):
    q = me.dynamicsymbols("q1:%d" % (n_links + 1))
    u = me.dynamicsymbols("u1:%d" % (n_links + 1))
    world = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(world, 0)
    bodies, loads = [], []
    parent_frame, parent_point, parent_length = world, origin, 0.1
    for i in range(1, n_links + 1):
        xyz, rpy, axis, _ = chain.joint_data(i, parent_length)
        joint_frame = me.ReferenceFrame("F%d" % i)
        joint_frame.orient_body_fixed(parent_frame, (rpy[2], rpy[1], rpy[0]), "zyx")
        a = [float(c) for c in axis.split()]
        link = me.ReferenceFrame("B%d" % i)
        link.orient_axis(joint_frame, a[0] * joint_frame.x + a[1] * joint_frame.y + a[2] * joint_frame.z, q[i - 1])
        link.set_ang_vel(joint_frame, u[i - 1] * (a[0] * joint_frame.x + a[1] * joint_frame.y + a[2] * joint_frame.z))
        joint_point = parent_point.locatenew("P%d" % i, xyz[0] * parent_frame.x + xyz[1] * parent_frame.y +
                                             xyz[2] * parent_frame.z)
        joint_point.v2pt_theory(parent_point, world, parent_frame)
        length, mass, com, inertia, irpy = chain.link_data(i)
        mass_centre = joint_point.locatenew("C%d" % i, com[0] * link.x + com[1] * link.y + com[2] * link.z)
        mass_centre.v2pt_theory(joint_point, world, link)
        r = rpy_matrix(irpy)
        tensor = r * sp.Matrix(inertia) * r.T  # the inertial frame's tensor in link axes
        dyadic = me.inertia(link, tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1], tensor[1, 2],
                            tensor[0, 2])
        bodies.append(me.RigidBody("L%d" % i, mass_centre, link, mass, (dyadic, mass_centre)))
        loads.append((mass_centre, -9.81 * mass * world.z))
        parent_frame, parent_point, parent_length = link, joint_point, length
    kinematics = [qi.diff(me.dynamicsymbols._t) - ui for qi, ui in zip(q, u)]
    return q, u, world, bodies, loads, kinematics


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: sympy_chain.py N")
    n_links = int(sys.argv[1])
    q, u, world, bodies, loads, kinematics = build(n_links)
    start = time.process_time()
    kane = me.KanesMethod(world, q_ind=q, u_ind=u, kd_eqs=kinematics)
    kane.kanes_equations(bodies, loads)
    mass = kane.mass_matrix
    seconds = time.process_time() - start
    state = {q[i]: 0.3 * math.sin(i + 1) for i in range(n_links)}
    state.update({u[i]: 0.5 * math.cos(i + 1) for i in range(n_links)})
    mass_values = [float(x.xreplace(state).evalf()) for x in mass]
    forcing_values = [float(x.xreplace(state).evalf()) for x in kane.forcing]
    print(json.dumps({"links": n_links, "seconds": seconds, "mass": mass_values, "forcing": forcing_values}))


if __name__ == "__main__":
    main()
