"""Makes the freshly built gauss_core importable: GAUSS_BUILD_DIR/python (default: <repo>/build),
and the measurements shared with the Blender tests (tests/common)."""
import os
import pathlib
import sys

REPO = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build"))
sys.path.insert(0, str(BUILD / "python"))
sys.path.insert(0, str(REPO / "tests" / "common"))
SHARED_MESHES = REPO.parent / "shared" / "meshes"

# Under CI=true a skip is a failure unless its reason is allowed; the summary prints the skips.
from ci_skips import pytest_runtest_makereport, pytest_terminal_summary  # noqa: E402,F401
