# SPDX-License-Identifier: GPL-2.0-or-later
"""The model library in the runner cache: built once, reused, rebuilt when
changed after it was built (never loaded as it is), its own entry."""
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import model_path

LOAD = """
import sys, kanegen
m = kanegen.load(sys.argv[1])
print(m.library)
print(repr(float(m.forward_dynamics([0.5], [0.0])[0])))
"""


def load_in_a_process(tmp_path):
    env = dict(os.environ, KANEGEN_CACHE_DIR=str(tmp_path / "cache"))
    done = subprocess.run([sys.executable, "-c", LOAD, model_path("simple_pendulum.json")], env=env,
                          capture_output=True, text=True, check=True)
    library, value = done.stdout.split()
    return library, float(value), done.stderr


def test_library_is_cached_and_a_changed_one_rebuilt(tmp_path):
    library, value, _ = load_in_a_process(tmp_path)
    assert os.path.basename(library) == "kernels.so"
    assert os.path.basename(os.path.dirname(library)).startswith("library-")
    assert os.path.exists(os.path.join(os.path.dirname(library), "manifest"))
    before = os.stat(library).st_mtime_ns
    again, _, messages = load_in_a_process(tmp_path)
    assert again == library and os.stat(library).st_mtime_ns == before and "rebuilding" not in messages
    with open(library, "ab") as f:  # changed after it was built
        f.write(b"\0")
    again, value_after, messages = load_in_a_process(tmp_path)
    assert "the cached model library in" in messages and "kernels.so changed after it was built" in messages
    assert value_after == value
    _, _, messages = load_in_a_process(tmp_path)  # the rebuilt one is intact
    assert "rebuilding" not in messages


def test_dynamics_methods_agree(kanegen):
    # The articulated-body recursion and composite inertias + LDL^T: two
    # derivations of forward_dynamics, two cache entries.
    recursive = kanegen.load(model_path("arm7.urdf"), dynamics="recursive")
    composite = kanegen.load(model_path("arm7.urdf"), dynamics="composite")
    assert recursive.library != composite.library
    rng = np.random.default_rng(3)
    Q, U, T = rng.uniform(-1, 1, (20, 7)), rng.uniform(-1, 1, (20, 7)), rng.uniform(-5, 5, (20, 7))
    assert recursive.forward_dynamics(Q, U, T) == pytest.approx(composite.forward_dynamics(Q, U, T),
                                                                rel=1e-9, abs=1e-9)
