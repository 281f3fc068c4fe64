"""native.py finds the solver the way the add-on was installed (it needs no bpy, so it is loaded here).

- Classic zip: the module sits in the add-on folder, and that copy is used even when another
  gauss_core (e.g. an extension's wheel of another version) is importable at the top level.
- Extension: the wheel installs gauss_core as a top-level module; the add-on folder holds none.
Each case runs in a fresh interpreter, with the add-on's native.py and errors.py copied into a package.
"""
import importlib.machinery
import importlib.util
import pathlib
import shutil
import subprocess
import sys
import textwrap

import pytest

from conftest import REPO

SUFFIX = importlib.machinery.EXTENSION_SUFFIXES[0]


@pytest.fixture
def built_module():
    """The gauss_core these tests import (the build tree's, conftest.py, or the installed wheel's)."""
    spec = importlib.util.find_spec("gauss_core")
    assert spec is not None and spec.origin.endswith(SUFFIX), spec
    return pathlib.Path(spec.origin)


def make_addon(root, bundled=None):
    package = root / "lookup_addon"
    package.mkdir()
    for name in ("native.py", "errors.py"):
        shutil.copy(REPO / "python_addon" / "gauss_stylization" / name, package / name)
    (package / "__init__.py").write_text("")
    if bundled is not None:
        shutil.copy(bundled, package / bundled.name)
    return package


def core_file(root, top_level_dir):
    """Where native.core() found gauss_core, with top_level_dir first on sys.path."""
    script = textwrap.dedent("""
        import sys
        sys.path[:0] = [%r, %r]
        from lookup_addon import native
        print("FOUND", native.core().__file__)
    """ % (str(root), str(top_level_dir)))
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    return pathlib.Path(result.stdout.split("FOUND", 1)[1].strip())


def test_classic_install_uses_its_bundled_module_over_a_top_level_one(built_module, tmp_path):
    (tmp_path / "addon_root").mkdir()
    package = make_addon(tmp_path / "addon_root", bundled=built_module)
    stale = tmp_path / "site"
    stale.mkdir()
    shutil.copy(built_module, stale / built_module.name)  # another copy, importable as top-level gauss_core
    assert core_file(package.parent, stale) == package / built_module.name


def test_extension_install_imports_the_top_level_module(built_module, tmp_path):
    (tmp_path / "addon_root").mkdir()
    package = make_addon(tmp_path / "addon_root")
    site = tmp_path / "site"  # what Blender's extension system makes of the wheel
    site.mkdir()
    shutil.copy(built_module, site / built_module.name)
    assert core_file(package.parent, site) == site / built_module.name
