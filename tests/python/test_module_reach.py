"""The module loads where official Blender builds run (glibc 2.28): auditwheel checks the wheel.

auditwheel (pinned in packaging/tools-requirements.txt) reads what the module needs from the system, the
shared libraries and the glibc (and libstdc++) symbol versions, against the manylinux_2_28 policy; a new
runtime dependency or a newer symbol version makes the wheel need a later manylinux, and
scripts/build_wheel.sh's `auditwheel repair --plat manylinux_2_28_x86_64` fail. Built on Debian 12
(glibc 2.36), the module only qualifies because cpp/python/glibc_baseline.cpp binds the few symbols whose
default version is newer than 2.28 to their old versions (CMakeLists.txt, Reach). What auditwheel does
not check is checked here with readelf: the module exports Python's entry point only, and keeps its
pybind11 internals apart from other add-ons' modules.
"""
import glob
import pathlib
import platform
import re
import shutil
import subprocess

import pytest

from conftest import BUILD
from wheel_build import build_wheel, tools_venv

pytestmark = pytest.mark.skipif(
    platform.system() != "Linux" or platform.machine() != "x86_64" or shutil.which("readelf") is None,
    reason="the checks are for x86-64 Linux modules (auditwheel, readelf from binutils)")

POLICY = (2, 28)  # manylinux_2_28: the glibc official Blender builds target


@pytest.fixture(scope="module")
def shipped_module():
    """The module as the add-on ships it (BUILD/addon/gauss_stylization, what the zips contain)."""
    found = glob.glob(str(BUILD / "addon" / "gauss_stylization" / "gauss_core*.so"))
    if len(found) != 1:
        pytest.fail("expected one staged gauss_core*.so in %s, found %s: build first" % (BUILD, found))
    return pathlib.Path(found[0])


def test_auditwheel_finds_the_wheel_within_manylinux_2_28():
    wheel = build_wheel()
    assert wheel.name.endswith("-manylinux_2_28_x86_64.whl")  # build_wheel.sh's repair took that tag
    result = subprocess.run([str(tools_venv() / "bin" / "auditwheel"), "show", str(wheel)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    text = " ".join(result.stdout.split())
    consistent = re.search(r'consistent with the following platform tag: "manylinux_(\d+)_(\d+)_x86_64"', text)
    assert consistent, text
    assert tuple(map(int, consistent.groups())) <= POLICY, text
    assert "libc.so.6" in text, text  # the report was read: every module needs glibc


def test_exports_only_the_python_entry_point(shipped_module):
    table = subprocess.run(["readelf", "-W", "--dyn-syms", str(shipped_module)], check=True,
                           capture_output=True, text=True).stdout
    defined = [fields[7].split("@")[0] for fields in (line.split() for line in table.splitlines())
               if len(fields) >= 8 and fields[0].rstrip(":").isdigit() and fields[6] != "UND"]
    assert defined == ["PyInit_gauss_core"], defined


def test_pybind11_internals_are_its_own(shipped_module):
    # pybind11 shares C++ objects and exception translators between modules whose internals id
    # matches; with a private C++ runtime the module must not share them (CMakeLists.txt, Reach).
    assert b"_libstdcpp_private_gauss" in shipped_module.read_bytes()
