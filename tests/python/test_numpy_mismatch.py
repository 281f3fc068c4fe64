"""A module that meets a numpy it cannot read refuses to load, and the add-on says so; nothing crashes.

The real mismatch: gauss_core built with Debian 12's pybind11 2.10 (which reads numpy 2's dtypes at
numpy 1's offsets: item size 0) imported beside numpy 2. The module must raise ImportError at import
(cpp/python/numpy_abi_guard.h) and the add-on's native.core() must turn it into its readable message.
Without the guard the import succeeds and these tests fail. They need numpy 2 in the Python running
them (scripts/test_numpy2.sh) and Debian's pybind11-dev; the build (build-wheel-pybind210-cpXY, ~45 s
the first time, incremental after) uses CMake's GAUSS_ALLOW_OLD_PYBIND11, which exists for this only.
"""
import importlib.machinery
import pathlib
import shutil
import subprocess
import sys
import textwrap

import numpy
import pytest

from conftest import REPO

OLD_PYBIND11 = pathlib.Path("/usr/lib/cmake/pybind11")  # Debian's pybind11-dev (2.10)
TAG = "cp%d%d" % sys.version_info[:2]

pytestmark = [
    pytest.mark.skipif(int(numpy.__version__.split(".")[0]) < 2,
                       reason="needs numpy 2 (scripts/test_numpy2.sh runs this file with it)"),
    pytest.mark.skipif(not (OLD_PYBIND11 / "pybind11Config.cmake").is_file(),
                       reason="needs Debian's pybind11-dev 2.10 (scripts/install_deps.sh installs it)"),
]


@pytest.fixture(scope="module")
def old_pybind11_module():
    """gauss_core built with pybind11 2.10 for this Python."""
    build = REPO / ("build-wheel-pybind210-" + TAG)
    configure = ["cmake", "-S", str(REPO), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                 "-DGAUSS_BUILD_TESTS=OFF", "-DGAUSS_BUILD_BENCH=OFF", "-DGAUSS_ALLOW_OLD_PYBIND11=ON",
                 "-Dpybind11_DIR:PATH=%s" % OLD_PYBIND11, "-DPython_EXECUTABLE=%s" % sys.executable]
    for command in (configure, ["cmake", "--build", str(build), "-j2", "--target", "gauss_core"]):
        result = subprocess.run(command, capture_output=True, text=True)
        assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    used = [line.partition("=")[2] for line in (build / "CMakeCache.txt").read_text().splitlines()
            if line.startswith("pybind11_DIR:")]
    assert used == [str(OLD_PYBIND11)], used  # really the old pybind11
    found = sorted((build / "python").glob("gauss_core" + importlib.machinery.EXTENSION_SUFFIXES[0]))
    assert len(found) == 1, found
    return found[0]


def run_python(code, path):
    """Runs code in a fresh interpreter with `path` first on sys.path; (exit code, output)."""
    script = "import sys; sys.path.insert(0, %r)\n" % str(path) + textwrap.dedent(code)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    return result.returncode, result.stdout + result.stderr


def test_the_module_refuses_to_load(old_pybind11_module):
    code, output = run_python("""
        import numpy
        try:
            import gauss_core
        except ImportError as exc:
            print("REFUSED:", exc)
        else:
            print("LOADED", gauss_core.__file__)
    """, old_pybind11_module.parent)
    assert code == 0, output  # a negative code would be the crash this prevents
    assert "REFUSED:" in output, output
    assert "pybind11 2.10" in output and "numpy %s" % numpy.__version__ in output, output


def test_the_add_on_shows_its_message(old_pybind11_module, tmp_path):
    # The add-on's native.py (a classic install: the module bundled in the add-on folder), loaded
    # without bpy; core() must raise NativeModuleError with the add-on's message, never crash.
    package = tmp_path / "gauss_mismatch_addon"
    package.mkdir()
    source = REPO / "python_addon" / "gauss_stylization"
    for name in ("native.py", "errors.py"):
        shutil.copy(source / name, package / name)
    (package / "__init__.py").write_text("")
    shutil.copy(old_pybind11_module, package / old_pybind11_module.name)
    code, output = run_python("""
        from gauss_mismatch_addon import native
        try:
            native.core()
        except native.NativeModuleError as exc:
            print("MESSAGE:", exc)
        else:
            print("LOADED")
    """, tmp_path)
    assert code == 0, output
    assert "MESSAGE: The Gauss solver (gauss_core native module) cannot load" in output, output
    assert "numpy %s" % numpy.__version__ in output and "pybind11 2.10" in output, output
