# SPDX-License-Identifier: GPL-2.0-or-later
"""kanegen's errors as Python exceptions carrying its messages."""
import os

import pytest

from conftest import model_path

BAD = os.environ.get("KANEGEN_BAD_MODELS_DIR",
                     os.path.join(os.path.dirname(__file__), "..", "data", "bad_models"))


def test_exception_hierarchy(kanegen):
    for error in (kanegen.ModelError, kanegen.BuildError, kanegen.MissingKernelError, kanegen.DynamicsError,
                  kanegen.SimulationError):
        assert issubclass(error, kanegen.Error)
    assert kanegen.ModelError.__module__ == "kanegen"


def test_bad_model_is_a_model_error_with_file_and_place(kanegen):
    path = os.path.join(BAD, "duplicate_joint.json")
    with pytest.raises(kanegen.ModelError) as caught:
        kanegen.load(path)
    error = caught.value
    assert error.file == path
    assert error.place.startswith("/joints")
    assert str(error).startswith(path + ": " + error.place + ": ")


def test_missing_file_is_a_model_error(kanegen, tmp_path):
    path = str(tmp_path / "nothing.json")
    with pytest.raises(kanegen.Error, match="nothing.json"):
        kanegen.load(path)


def test_bad_load_options(kanegen):
    with pytest.raises(ValueError, match="precision must be \"double\""):
        kanegen.load(model_path("simple_pendulum.json"), precision="float")
    with pytest.raises(ValueError, match="dynamics must be"):
        kanegen.load(model_path("simple_pendulum.json"), dynamics="fast")


def test_compiler_failure_is_a_build_error(kanegen, tmp_path, monkeypatch):
    monkeypatch.setenv("KANEGEN_CACHE_DIR", str(tmp_path / "cache"))
    # A compiler that fails with a message: the message ends the exception's
    # (a notebook shows no stderr).
    compiler = tmp_path / "cxx"
    compiler.write_text("#!/bin/sh\necho 'fatal error: no room for kernels' >&2\nexit 1\n")
    compiler.chmod(0o700)
    monkeypatch.setenv("KANEGEN_CXX", str(compiler))
    with pytest.raises(kanegen.BuildError, match="did not compile.*the compiler said:\nfatal error: no room"):
        kanegen.load(model_path("simple_pendulum.json"))
    assert not list((tmp_path / "cache").glob("library-*/kernels.so*"))
    assert not list((tmp_path / "cache").glob("library-*/compile.log"))
    # Nothing half-built stays: with a working compiler the same entry builds.
    monkeypatch.delenv("KANEGEN_CXX")
    monkeypatch.setenv("CXX", "c++")
    m = kanegen.load(model_path("simple_pendulum.json"))
    assert m.library.startswith(str(tmp_path / "cache"))
