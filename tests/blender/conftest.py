"""Fixtures for the add-on tests run inside Blender (see run_headless.py)."""

import pytest

import helpers
# Under CI=true a skip is a failure unless its reason is allowed; the summary prints the skips.
from ci_skips import pytest_runtest_makereport, pytest_terminal_summary  # noqa: F401  (helpers: on sys.path)


@pytest.fixture(scope="session")
def addon():
    """The add-on package loaded from BUILD_DIR/addon (helpers put it on sys.path) and registered once."""
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
