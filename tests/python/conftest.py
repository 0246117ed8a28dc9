"""Paths of the C programs the tests compare with, from the meson test's environment
(python/meson.build); a test that needs one it is not given is skipped."""
import os

import pytest

ROOT = os.environ.get("BGDAE_SOURCE_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


def program(var):
    path = os.environ.get(var)
    if not path or not os.access(path, os.X_OK):
        pytest.skip(f"{var} not set (run through meson test)")
    return path


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def pendulum_ref():
    return program("BGDAE_PENDULUM_REF")


@pytest.fixture
def bgsim():
    return program("BGDAE_BGSIM")
