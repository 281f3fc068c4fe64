"""The built module loads where official Blender builds run: readelf shows what it needs from the system.

The allowance (glibc's own libraries, glibc symbol versions up to 2.28, one exported symbol) lives in
scripts/module_reach.py; README.md, "Which Blender can load this build", explains it. A new runtime
dependency or a newer glibc symbol fails here with the symbols that need it.
"""
import glob
import pathlib
import platform
import shutil
import sys

import pytest

from conftest import BUILD, REPO

sys.path.insert(0, str(REPO / "scripts"))
import module_reach  # noqa: E402

pytestmark = pytest.mark.skipif(
    platform.system() != "Linux" or platform.machine() != "x86_64" or shutil.which("readelf") is None,
    reason="the allowance is for x86-64 Linux modules, read with readelf (binutils)")


@pytest.fixture(scope="module")
def shipped_module():
    """The module as the add-on ships it (BUILD/addon/gauss_stylization, what the zips contain)."""
    found = glob.glob(str(BUILD / "addon" / "gauss_stylization" / "gauss_core*.so"))
    if len(found) != 1:
        pytest.fail("expected one staged gauss_core*.so in %s, found %s: build first" % (BUILD, found))
    return pathlib.Path(found[0])


def test_needs_only_glibc_libraries(shipped_module):
    needed = module_reach.needed_libraries(shipped_module)
    assert "libc.so.6" in needed
    assert set(needed) <= set(module_reach.ALLOWED_NEEDED), needed


def test_glibc_symbol_versions_within_allowance(shipped_module):
    versions = module_reach.required_versions(shipped_module)
    assert "GLIBC_2.2.5" in versions  # readelf's output was understood: every glibc module needs it
    beyond = [line for line in module_reach.problems(shipped_module) if "needs" in line]
    assert not beyond, "\n".join(beyond)
    assert module_reach.newest_glibc(shipped_module) <= module_reach.GLIBC_ALLOWANCE


def test_exports_only_the_python_entry_point(shipped_module):
    exported = [name for name, _, defined in module_reach.dynamic_symbols(shipped_module) if defined]
    assert exported == list(module_reach.EXPORTS)


def test_pybind11_internals_are_its_own(shipped_module):
    # pybind11 shares C++ objects and exception translators between modules whose internals id
    # matches; with a private C++ runtime the module must not share them (CMakeLists.txt, Reach).
    assert b"_libstdcpp_private_gauss" in shipped_module.read_bytes()
