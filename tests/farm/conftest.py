"""Fixtures of the farm tests (tests/farm): the engines studios run (Slurm, Open Job Description,
Flamenco) baking a shot in chunks through the add-on's bake/farm_cli.py, compared with one bake.

Needs Debian's `blender`, the build's staged add-on (GAUSS_BUILD_DIR, default <repo>/build), and per
engine: slurm-wlm and munge (run as root), openjd-cli in the tools venv, node
(scripts/install_deps.sh installs them all). A missing one fails its test: nothing is skipped.
Run them with /usr/bin/python3 (scripts/run_tests.sh does): a Blender started from pyenv's python3
takes pyenv's Python library path and no longer finds Debian's numpy.
"""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[1]
BUILD = pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")).resolve()
FARM_CLI = BUILD / "addon" / "gauss_stylization" / "bake" / "farm_cli.py"
SHOT_FRAMES = (1, 48)
CHUNKS = 4
OBJECT = "Capsule"
BAKE_TIMEOUT = 300  # seconds for a whole farm run; the tests bound every wait

sys.path.insert(0, str(HERE))
sys.path.insert(0, str(REPO / "tests" / "common"))

# Under CI=true a skip is a failure unless its reason is allowed; the summary prints the skips.
from ci_skips import pytest_runtest_makereport, pytest_terminal_summary  # noqa: E402,F401


def blender():
    found = shutil.which("blender")
    if not found:
        pytest.fail("no blender on PATH (bash scripts/install_deps.sh installs Debian's)")
    return found


def run(argv, **options):
    """Run ``argv`` with no stdin, bounded in time; fail the test with its output if it fails."""
    result = subprocess.run([str(part) for part in argv], capture_output=True, text=True, stdin=subprocess.DEVNULL,
                            timeout=options.pop("timeout", BAKE_TIMEOUT), **options)
    if result.returncode != 0:
        pytest.fail("%s exited with %d:\n%s\n%s" % (" ".join(map(str, argv)), result.returncode,
                                                   result.stdout[-3000:], result.stderr[-3000:]))
    return result


def farm_cli(blend, *args):
    """argv of one farm_cli.py job in a headless Blender (the factory settings: no user add-ons)."""
    return ([blender(), "-b"] + ([str(blend)] if blend else [])
            + ["--factory-startup", "--python-exit-code", "1", "-P", str(FARM_CLI), "--", *map(str, args)])


@pytest.fixture(scope="session")
def shot(tmp_path_factory):
    """A saved shot: the capsule bent over frames 1-48, Warm Start off (its settings in the .blend)."""
    if not FARM_CLI.is_file():
        pytest.fail("no add-on in %s: build the project first (bash scripts/build.sh)" % FARM_CLI.parent.parent)
    folder = tmp_path_factory.mktemp("shot")
    blend = folder / "shot.blend"
    run([blender(), "-b", "--factory-startup", "--python-exit-code", "1", "-P", HERE / "make_shot.py", "--",
         BUILD, blend, "--frames", "%d-%d" % SHOT_FRAMES])
    return blend


@pytest.fixture(scope="session")
def one_bake(shot):
    """The shot baked by one process: the reference every farm's merged cache must equal."""
    out = shot.parent / "one_process.pc2"
    run(farm_cli(shot, "bake", "--object", OBJECT, "--frames", "%d-%d" % SHOT_FRAMES, "--out", out))
    return out.read_bytes()


def assert_same_bytes(path, reference):
    data = pathlib.Path(path).read_bytes()
    assert len(data) == len(reference), "%s: %d bytes, one bake %d" % (path, len(data), len(reference))
    assert data == reference, "%s differs from the one-process bake" % path
