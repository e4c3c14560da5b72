# SPDX-License-Identifier: GPL-2.0-or-later
"""The kernels on NumPy arrays, against analytic values and independent paths
(the C++ runner's `kanegen eval`, Newton-Euler inverse dynamics)."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

from conftest import model_path

G = 9.81


def test_pendulum_forward_dynamics_is_the_analytic_one(pendulum):
    # A point mass m on a massless rod of length l: m l^2 theta'' = -m g l sin(theta) + tau.
    for theta, omega, tau in [(0.5, 0.0, 0.0), (-1.2, 3.0, 0.0), (2.5, -1.0, 0.7)]:
        udot = pendulum.forward_dynamics([theta], [omega], [tau])
        assert udot.shape == (1,)
        assert udot[0] == pytest.approx(-G * math.sin(theta) + tau, rel=1e-14, abs=1e-14)
    m, l = 3.0, 2.0
    udot = pendulum.forward_dynamics([0.5], [0.0], [0.7], params={"m": m, "l": l})
    assert udot[0] == pytest.approx(-G / l * math.sin(0.5) + 0.7 / (m * l * l), rel=1e-14)


def test_pendulum_energies_outputs_and_mass_matrix(pendulum):
    m, l = 2.0, 1.5
    params = {"m": m, "l": l}
    theta, omega = 0.8, 1.7
    assert pendulum.mass_matrix([theta], params=params) == pytest.approx(np.array([[m * l * l]]), rel=1e-14)
    assert pendulum.kinetic_energy([theta], [omega], params=params) == pytest.approx(0.5 * m * l * l * omega**2)
    v = [pendulum.potential_energy([a], params=params) for a in (0.0, theta)]
    assert v[1] - v[0] == pytest.approx(m * G * l * (1 - math.cos(theta)), rel=1e-13)
    y = pendulum.outputs([theta], [omega], params=params)
    assert pendulum.output_names == ["bob.x", "bob.y", "bob.z", "angle"]
    assert y == pytest.approx([-l * math.sin(theta), 0.0, -l * math.cos(theta), theta], abs=1e-14)
    # The generalized gravity force is dV/dq.
    assert pendulum.gravity([theta], params=params)[0] == pytest.approx(m * G * l * math.sin(theta), rel=1e-13)


def test_names_and_parameters(pendulum):
    assert pendulum.name == "simple_pendulum"
    assert pendulum.coordinates == ["pivot"]
    assert pendulum.nq == 1 and pendulum.nu == 1
    assert pendulum.parameters == {"m": 1.0, "l": 1.0, "g": 9.81}
    assert pendulum.q0.tolist() == [0.5] and pendulum.u0.tolist() == [0.0]
    assert "forward_dynamics" in pendulum.kernels and "linearize" not in pendulum.kernels
    q, u = pendulum.initial_state()
    assert q.tolist() == [0.5] and u.tolist() == [0.0]


def test_set_parameters_changes_the_kernels_and_reset_restores(kanegen):
    m = kanegen.load(model_path("simple_pendulum.json"))
    m.set_parameters({"g": 1.0})
    assert m.parameters["g"] == 1.0
    assert m.forward_dynamics([0.5], [0.0])[0] == pytest.approx(-math.sin(0.5), rel=1e-14)
    with pytest.raises(KeyError, match="no parameter of that name.*m, l, g"):
        m.set_parameters({"g": 2.0, "mass": 1.0})
    assert m.parameters["g"] == 1.0  # all or nothing
    m.reset_parameters()
    assert m.parameters == m.default_parameters
    with pytest.raises(KeyError, match="length"):
        m.forward_dynamics([0.5], [0.0], params={"length": 2.0})


def test_arm7_mass_matrix_is_symmetric_positive_definite_and_the_runners(arm7):
    q = np.linspace(-1.0, 1.2, 7)
    M = arm7.mass_matrix(q)
    assert M.shape == (7, 7)
    assert np.array_equal(M, M.T)
    assert np.all(np.linalg.eigvalsh(M) > 0)
    # The same model compiled into the C++ runner (kanegen eval, another
    # process and another build of the kernels): the same numbers.
    exe = os.environ.get("KANEGEN_EXE")
    if not exe:
        pytest.skip("KANEGEN_EXE not set (ctest sets it)")
    out = subprocess.run([exe, "eval", model_path("arm7.urdf"), "--q", ",".join(repr(x) for x in q)],
                         check=True, capture_output=True, text=True).stdout
    runner = json.loads(out)
    assert np.array(runner["mass_matrix"]) == pytest.approx(M, rel=1e-14, abs=1e-15)
    u = np.zeros(7)
    assert np.array(runner["udot"]) == pytest.approx(arm7.forward_dynamics(q, u), rel=1e-12, abs=1e-12)


def test_arm7_kernels_agree_with_each_other(arm7):
    rng = np.random.default_rng(1)
    q, u, tau = rng.uniform(-1, 1, 7), rng.uniform(-1, 1, 7), rng.uniform(-5, 5, 7)
    M = arm7.mass_matrix(q)
    f = arm7.forcing(q, u, tau)
    udot = arm7.forward_dynamics(q, u, tau)
    assert M @ udot == pytest.approx(f, rel=1e-10, abs=1e-10)
    # Newton-Euler's recursion (M never formed) gives back the inputs.
    assert arm7.inverse_dynamics(q, u, udot) == pytest.approx(tau, rel=1e-9, abs=1e-9)
    assert arm7.kinetic_energy(q, u) == pytest.approx(0.5 * u @ M @ u, rel=1e-12)


def test_batch_equals_row_by_row(arm7):
    rng = np.random.default_rng(2)
    n = 50
    Q, U, T = rng.uniform(-1, 1, (n, 7)), rng.uniform(-1, 1, (n, 7)), rng.uniform(-3, 3, (n, 7))
    udot = arm7.forward_dynamics(Q, U, T)
    M = arm7.mass_matrix(Q)
    T_kin = arm7.kinetic_energy(Q, U)
    assert udot.shape == (n, 7) and M.shape == (n, 7, 7) and T_kin.shape == (n,)
    for i in range(n):
        assert np.array_equal(udot[i], arm7.forward_dynamics(Q[i], U[i], T[i]))
        assert np.array_equal(M[i], arm7.mass_matrix(Q[i]))
        assert T_kin[i] == arm7.kinetic_energy(Q[i], U[i])
    # A 1-D input is used for every row; tau omitted is zeros.
    assert np.array_equal(arm7.forward_dynamics(Q, U, T[0]), np.array([arm7.forward_dynamics(Q[i], U[i], T[0])
                                                                     for i in range(n)]))
    assert np.array_equal(arm7.forward_dynamics(Q, U), arm7.forward_dynamics(Q, U, np.zeros((n, 7))))


def test_inputs_are_converted_and_checked(arm7):
    q = np.linspace(0, 1, 7)
    expected = arm7.mass_matrix(q)
    assert np.array_equal(arm7.mass_matrix(q.tolist()), expected)
    assert np.array_equal(arm7.mass_matrix(q.astype(np.float32).astype(np.float64)), arm7.mass_matrix(q.astype(np.float32)))
    read_only = q.copy()
    read_only.flags.writeable = False
    assert np.array_equal(arm7.mass_matrix(read_only), expected)
    assert np.array_equal(arm7.mass_matrix(np.broadcast_to(q, (3, 7)))[1], expected)
    assert np.array_equal(arm7.mass_matrix(q[::-1][::-1]), expected)
    Q = np.asfortranarray(np.tile(q, (3, 1)))
    assert np.array_equal(arm7.mass_matrix(Q)[2], expected)
    with pytest.raises(ValueError, match=r"mass_matrix: q must have shape \(7,\) or \(N, 7\).*got \(6,\)"):
        arm7.mass_matrix(np.zeros(6))
    with pytest.raises(ValueError, match=r"got \(2, 3, 7\)"):
        arm7.mass_matrix(np.zeros((2, 3, 7)))
    with pytest.raises(ValueError, match="u has 4 rows, the arrays before it 3"):
        arm7.forward_dynamics(np.zeros((3, 7)), np.zeros((4, 7)))
    with pytest.raises(TypeError, match="q must be an array of numbers"):
        arm7.mass_matrix("abc")


def test_missing_kernel_says_which_option_generates_it(kanegen, pendulum):
    with pytest.raises(kanegen.MissingKernelError, match=r"controller=True"):
        pendulum.linearize([0.1], [0.0])
    with pytest.raises(kanegen.MissingKernelError, match=r"jacobians=True"):
        pendulum.forcing_jacobian([0.1], [0.0])
    with pytest.raises(kanegen.MissingKernelError, match="closed loops"):
        pendulum.constraints([0.1])


def test_linearize_of_the_pendulum_is_the_analytic_one(kanegen):
    m = kanegen.load(model_path("simple_pendulum.json"), controller=True)
    mass, l, theta = 2.0, 0.5, 0.3
    A, B = m.linearize([theta], [0.0], [0.0], params={"m": mass, "l": l})
    assert A == pytest.approx(np.array([[0.0, 1.0], [-G / l * math.cos(theta), 0.0]]), abs=1e-13)
    assert B == pytest.approx(np.array([[0.0], [1.0 / (mass * l * l)]]), rel=1e-13)
    assert m.coriolis_matrix([theta], [1.0]).shape == (1, 1)


def test_singular_mass_matrix_is_a_dynamics_error(kanegen, pendulum):
    with pytest.raises(kanegen.DynamicsError, match="singular"):
        pendulum.forward_dynamics([0.5], [0.0], params={"m": 0.0})
    with pytest.raises(kanegen.DynamicsError, match="at row 0"):
        pendulum.forward_dynamics(np.zeros((3, 1)), np.zeros((3, 1)), params={"m": 0.0})


def test_closed_loop_kernels(kanegen):
    four_bar = kanegen.load(model_path("four_bar.json"))
    assert four_bar.nc > 0 and "constraints" in four_bar.kernels
    q, u = four_bar.initial_state()
    phi = four_bar.constraints(q)
    assert phi.shape == (four_bar.nc,)
    assert np.max(np.abs(phi)) < 1e-8  # the initial state closes the loop
    C = four_bar.constraint_jacobian(q)
    assert C.shape == (four_bar.nc, four_bar.nu)
    udot, lam = four_bar.constrained_dynamics(q, u)
    assert C @ udot == pytest.approx(four_bar.constraint_bias(q, u), abs=1e-9)
    assert lam.shape == (four_bar.nc,)
