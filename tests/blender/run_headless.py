"""Run the add-on's pytest suite inside Blender (headless).

    blender -b --factory-startup --python-exit-code 1 -P tests/blender/run_headless.py -- BUILD_DIR [pytest args]
    python tests/blender/run_headless.py -- BUILD_DIR [pytest args]    (a Python with `bpy`, Blender as a module)

BUILD_DIR (default: <repo>/build) must hold addon/gauss_stylization with the
compiled gauss_core module, as staged by the CMake build; GAUSS_ADDON_DIR, when
set, names another folder holding the gauss_stylization package to test (where
Blender installed it: scripts/test_blender_versions.sh). Exits with pytest's
status, so any failure makes Blender exit non-zero. Prints its own totals last,
"blender headless: N passed, N failed, N skipped"; under CI=true a skip whose
reason is not on tests/common/ci_skips.py's allow-list counts as failed.
"""

import os
import sys

import bpy  # noqa: F401  (in a bpy module Blender starts here; inside Blender it is already loaded)

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


class Totals:
    """Counts the tests' outcomes (a test fails if any of its phases does)."""

    def __init__(self):
        self.outcome = {}

    def pytest_runtest_logreport(self, report):
        before = self.outcome.get(report.nodeid)
        if report.failed or before == "failed":
            self.outcome[report.nodeid] = "failed"
        elif report.skipped:
            self.outcome[report.nodeid] = "skipped"
        elif report.when == "call":
            self.outcome[report.nodeid] = "passed"

    def line(self):
        counts = [sum(1 for o in self.outcome.values() if o == kind) for kind in ("passed", "failed", "skipped")]
        return "blender headless: %d passed, %d failed, %d skipped" % tuple(counts)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    build = os.path.abspath(argv[0] if argv else os.path.join(REPO, "build"))
    os.environ["GAUSS_BUILD_DIR"] = build
    import pytest
    # Neither bytecode nor pytest's cache: the suite must not write into the source tree.
    sys.dont_write_bytecode = True
    totals = Totals()
    status = int(pytest.main([HERE, "-p", "no:cacheprovider", "-ra", *argv[1:]], plugins=[totals]))
    print(totals.line(), flush=True)
    return status


status = main()
if not bpy.app.binary_path:  # Blender as a Python module: see blender_process.exit_now
    sys.path.insert(0, HERE)
    from blender_process import exit_now
    exit_now(status)
sys.exit(status)
