# SPDX-License-Identifier: GPL-2.0-or-later
"""Model.simulate: the runtime's integrators in-process."""
import math

import numpy as np
import pytest

from conftest import model_path

G = 9.81


def test_free_pendulum_conserves_energy(pendulum):
    result = pendulum.simulate(10.0, integrator="dopri5", q0=[2.0], u0=[0.0], dt=0.01, rtol=1e-11, atol=1e-12)
    assert result.columns[:3] == ["t", "pivot", "pivot_dot"]
    assert len(result) == 1001 and result.t[-1] == pytest.approx(10.0)
    # The energy from the kernels, over every sample at once (a 2-D batch).
    q, u = result["pivot"][:, None], result["pivot_dot"][:, None]
    energy = pendulum.energy(q, u)
    assert np.max(np.abs(energy - energy[0])) < 1e-8
    assert np.ptp(result.pivot) > 3.0  # it swings (from 2 rad to -2 rad)


def test_small_swing_is_the_analytic_one(pendulum):
    theta0, l = 1e-3, 2.0
    result = pendulum.simulate(3.0, q0={"pivot": theta0}, set={"l": l}, dt=0.05, rtol=1e-12, atol=1e-14)
    expected = theta0 * np.cos(math.sqrt(G / l) * result.t)
    # The nonlinear pendulum differs by O(theta0^3).
    assert np.max(np.abs(result.pivot - expected)) < 1e-9
    assert pendulum.parameters["l"] == 1.0  # set= is for the run only


def test_energies_columns_and_pandas(pendulum):
    result = pendulum.simulate(0.5, dt=0.1, energies=True, stats=True)
    assert result.columns[-3:] == ["kinetic_energy", "potential_energy", "total_energy"]
    # The driver's energy columns are the kernels' on the same states.
    q, u = result.pivot[:, None], result.pivot_dot[:, None]
    assert np.array_equal(result.kinetic_energy, pendulum.kinetic_energy(q, u))
    assert "stats: integrator=dopri5" in result.messages
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="needs pandas"):
            result.to_pandas()
        return
    frame = result.to_pandas()
    assert list(frame.columns) == result.columns
    assert np.array_equal(frame["t"].to_numpy(), result.t)


def test_simulation_errors(kanegen, pendulum):
    with pytest.raises(kanegen.SimulationError, match="integrator"):
        pendulum.simulate(1.0, integrator="no-such-method")
    with pytest.raises(kanegen.MissingKernelError, match="jacobians=True"):
        pendulum.simulate(1.0, integrator="implicit")
    with pytest.raises(ValueError, match=r"q0 must have shape \(1,\)"):
        pendulum.simulate(1.0, q0=[1.0, 2.0])
    with pytest.raises(KeyError, match="no parameter"):
        pendulum.simulate(1.0, set={"nope": 1.0})
    with pytest.raises(TypeError, match="unexpected keyword"):
        pendulum.simulate(1.0, tolerance=1.0)


def test_implicit_integrator_with_jacobians(kanegen):
    m = kanegen.load(model_path("simple_pendulum.json"), jacobians=True)
    result = m.simulate(1.0, integrator="implicit", dt=0.1, rtol=1e-10, atol=1e-12)
    reference = m.simulate(1.0, integrator="dopri5", dt=0.1, rtol=1e-10, atol=1e-12)
    assert result.pivot == pytest.approx(reference.pivot, abs=1e-6)
