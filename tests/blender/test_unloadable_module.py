"""A gauss_core that cannot load: the add-on still works as far as it can and says why and what fixes it.

The message (native.load_failure_message) names the Python, numpy and glibc Blender runs, the modules
the add-on folder holds, and which build to install or make. The first tests load the add-on's
native.py from a throw-away package next to made-up module files; the last ones make the registered
add-on's own import fail and look at what Stylize and the panel show.
"""

import importlib
import importlib.machinery
import pathlib
import platform
import shutil
import sys
import types

import bpy
import numpy as np
import pytest

import helpers

PYTHON = "%d.%d" % sys.version_info[:2]
TAG = "cp%d%d" % sys.version_info[:2]
THIS_PYTHONS_MODULE = "gauss_core" + importlib.machinery.EXTENSION_SUFFIXES[0]


def _detected_versions():
    """What the message must report about this Blender."""
    return [platform.python_version(), np.__version__, platform.libc_ver()[1]]


@pytest.fixture
def native_beside(addon, tmp_path, monkeypatch):
    """native_beside({file name: bytes}) -> the add-on's native module, imported from a package of its
    own that holds the add-on's Python modules (an empty __init__, so nothing registers or loads
    eagerly) and, as its only gauss_core files, the given ones (a top-level gauss_core, which an
    installed extension's wheel is, cannot be imported meanwhile). The add-on's own gauss_core stays
    loaded and untouched."""
    monkeypatch.setitem(sys.modules, "gauss_core", None)
    loaded = []

    def load(files):
        name = "gauss_unloadable_%d" % len(loaded)
        package = tmp_path / name
        package.mkdir()
        for source in pathlib.Path(addon.native.__file__).parent.glob("*.py"):
            shutil.copy(source, package / source.name)
        (package / "__init__.py").write_text("")
        for file_name, data in files.items():
            (package / file_name).write_bytes(data)
        loaded.append(name)
        return importlib.import_module(name + ".native")

    sys.path.insert(0, str(tmp_path))
    yield load
    sys.path.remove(str(tmp_path))
    for name in loaded:
        for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
            del sys.modules[key]


def _failure(native):
    with pytest.raises(native.NativeModuleError) as info:
        native.core()
    message = str(info.value)
    for version in _detected_versions():
        assert version in message, (version, message)
    assert "Which Blender can load this build" in message  # where the README explains it
    assert str(info.value.__cause__) in message  # Python's own reason stays visible
    return message


def test_module_built_for_another_python(native_beside):
    other = "gauss_core.cpython-310-x86_64-linux-gnu.so" if PYTHON != "3.10" else \
        "gauss_core.cpython-311-x86_64-linux-gnu.so"
    message = _failure(native_beside({other: b"\x7fELF"}))
    built_for = "3.10" if PYTHON != "3.10" else "3.11"
    assert "only holds a module for Python %s (%s)" % (built_for, other) in message
    assert "install the add-on zip built for Python %s" % PYTHON in message
    assert "-%s-linux_x86_64.zip" % TAG in message


def test_module_for_this_python_that_does_not_load(native_beside):
    # What a module needing a newer glibc (or a damaged file) looks like: the file is there, the
    # loader refuses it.
    message = _failure(native_beside({THIS_PYTHONS_MODULE: b"not a shared object " * 8}))
    assert "the module for Python %s is there but does not load" % PYTHON in message
    assert "build the module on this machine" in message


def test_no_module_at_all(native_beside):
    message = _failure(native_beside({}))
    assert "holds no gauss_core module at all" in message
    assert "install the add-on zip built for Python %s" % PYTHON in message


@pytest.fixture
def unloadable(addon, monkeypatch):
    """The registered add-on with an import of its gauss_core that fails (ImportError)."""
    monkeypatch.setattr(addon.native, "_core", None)
    monkeypatch.delattr(addon, "gauss_core", raising=False)  # set on the package by the first import
    monkeypatch.setitem(sys.modules, addon.__name__ + ".gauss_core", None)  # makes importing it fail
    monkeypatch.setitem(sys.modules, "gauss_core", None)  # and the top-level one (an extension's wheel)
    return addon


def test_stylize_reports_it_and_leaves_the_mesh(unloadable):
    obj = helpers.suzanne(levels=0)
    before = helpers.coords(obj)
    with pytest.raises(RuntimeError, match=r"gauss_core native module\) cannot load") as info:
        bpy.ops.object.gauss_stylize(iterations=3)
    for version in _detected_versions():
        assert version in str(info.value)
    assert np.array_equal(helpers.coords(obj), before)
    assert len(obj.gauss_stylization.styles) == 0  # a failed start changes no setting either


class _LayoutRecorder:
    """Stands in for a UILayout: every call returns the recorder; label texts are kept."""

    def __init__(self):
        self.texts = []

    def label(self, text="", **_):
        self.texts.append(text)
        return self

    def __getattr__(self, name):
        return lambda *args, **kwargs: self


def test_panel_shows_it(unloadable):
    layout = _LayoutRecorder()  # no object selected: the panel draws the message and a hint only
    panel = unloadable.ui.VIEW3D_PT_gauss_stylization
    panel.draw(types.SimpleNamespace(layout=layout), bpy.context)
    shown = " ".join(layout.texts)
    assert "cannot load" in shown and "Fix:" in shown
    for version in _detected_versions():
        assert version in shown
