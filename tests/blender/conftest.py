"""Fixtures for the add-on tests run inside Blender (see run_headless.py)."""

import os
import sys

import pytest

import helpers


def _build_dir():
    return os.environ.get("GAUSS_BUILD_DIR", os.path.join(helpers.REPO, "build"))


@pytest.fixture(scope="session")
def addon():
    """The add-on package loaded from BUILD_DIR/addon and registered once."""
    path = os.path.join(_build_dir(), "addon")
    if not os.path.isdir(os.path.join(path, "gauss_stylization")):
        pytest.fail("no add-on in %s: build the project first (cmake --build build)" % path)
    sys.path.insert(0, path)
    import gauss_stylization
    gauss_stylization.register()
    yield gauss_stylization
    gauss_stylization.unregister()


@pytest.fixture(autouse=True)
def clean_scene(addon):
    """Every test starts with an empty scene."""
    helpers.clear_scene()
    yield
    helpers.clear_scene()
