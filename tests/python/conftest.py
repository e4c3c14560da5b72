# SPDX-License-Identifier: GPL-2.0-or-later
# The Python module's tests (run by ctest as python:*, tests/python/tests.cmake):
# the module from the build tree (PYTHONPATH), a private runner cache
# (KANEGEN_CACHE_DIR), the shipped models (KANEGEN_MODELS_DIR).
import os

import pytest

MODELS = os.environ.get("KANEGEN_MODELS_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "models"))


def model_path(name):
    return os.path.join(MODELS, name)


@pytest.fixture(scope="session")
def kanegen():
    import kanegen as module
    return module


@pytest.fixture(scope="session")
def pendulum(kanegen):
    return kanegen.load(model_path("simple_pendulum.json"))


@pytest.fixture(scope="session")
def arm7(kanegen):
    return kanegen.load(model_path("arm7.urdf"))
