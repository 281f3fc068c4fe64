"""The gauss_core wheel for the Python running the tests, built by scripts/build_wheel.sh (incremental:
~3 s when build-wheel-cpXY/ is current, ~45 s the first time on 2 cores), and the tools venv's path."""
import pathlib
import subprocess
import sys

from conftest import REPO

TAG = "cp%d%d" % sys.version_info[:2]


def tools_venv():
    """The pinned PyPI tools' venv (scripts/install_deps.sh makes it)."""
    result = subprocess.run(["bash", str(REPO / "scripts" / "install_deps.sh"), "--print-tools-venv"],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return pathlib.Path(result.stdout.strip().splitlines()[-1])


def build_wheel():
    """Path of the wheel for this Python (build-wheel-cpXY/dist)."""
    out = REPO / ("build-wheel-" + TAG) / "dist"
    result = subprocess.run(["bash", str(REPO / "scripts" / "build_wheel.sh"), sys.executable, str(out)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-4000:]
    wheel = pathlib.Path(result.stdout.strip().splitlines()[-1])
    assert wheel.is_file() and wheel.parent == out, result.stdout
    return wheel
