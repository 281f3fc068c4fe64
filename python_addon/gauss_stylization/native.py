"""Access to the compiled solver module ``gauss_core``.

The add-on must register (and show its panel) even when the native module is
missing or was built for another Python, so that the artist sees a readable
message instead of a traceback. Everything that needs the solver calls
``core()``, which raises ``NativeModuleError`` with that message.
"""

import sys

# Used only to build the preset menu when the native module cannot be loaded;
# the real list always comes from gauss_core.PRESETS (see docs/python_api.md).
FALLBACK_PRESETS = (
    "cube", "tetrahedron", "octahedron", "dodecahedron", "icosahedron",
    "square_pyramid", "truncated_pyramid", "triangular_prism", "hexagonal_prism",
    "plane", "cylinder", "cone", "double_cone",
)


class NativeModuleError(RuntimeError):
    """The solver module cannot be imported."""


def load_failure_message(exc):
    """What the artist reads when ``gauss_core`` cannot be imported: why, and which build fixes it.

    A module only loads in the Python version it was built for (its file name says which:
    gauss_core.cpython-311-x86_64-linux-gnu.so is for 3.11) and on a glibc at least as new as the
    one it needs, so the message names the Python, numpy and glibc this Blender runs and the
    modules the add-on folder holds (README: "Which Blender can load this build").
    """
    import glob
    import os
    import platform
    import re
    try:
        import numpy
        numpy_version = numpy.__version__
    except ImportError:
        numpy_version = "none importable"
    libc, libc_version = platform.libc_ver()
    python = "%d.%d" % sys.version_info[:2]
    folder = os.path.dirname(os.path.abspath(__file__))
    found = {}  # file name -> the Python it was built for
    for path in sorted(glob.glob(os.path.join(folder, "gauss_core*"))):
        built_for = re.search(r"\.cpython-(\d)(\d+)-", os.path.basename(path))
        found[os.path.basename(path)] = "%s.%s" % built_for.groups() if built_for else "unknown"
    if python in found.values():
        problem = "the module for Python %s is there but does not load on this system" % python
        fix = ("build the module on this machine (a GLIBC version in the import error means this "
               "system's glibc is older than the module needs)")
    else:
        problem = ("this add-on only holds " + ", ".join(
            "a module for Python %s (%s)" % (v, name) for name, v in found.items())
            if found else "this add-on holds no gauss_core module at all")
        fix = ("install the add-on zip built for Python %s (its name ends in -cp%d%d-linux_x86_64.zip) "
               "or build one against a Python %s" % (python, sys.version_info[0], sys.version_info[1], python))
    return ("The Gauss solver (gauss_core native module) cannot load: Blender runs Python %s with "
            "numpy %s on %s %s, and %s. Fix: %s; see the README, \"Which Blender can load this "
            "build\". (%s: %s)" % (platform.python_version(), numpy_version, libc or "a C library",
                                    libc_version or "of unknown version", problem, fix,
                                    type(exc).__name__, exc))


_core = None


def core():
    """Return the ``gauss_core`` module or raise NativeModuleError."""
    global _core
    if _core is None:
        try:
            from . import gauss_core as module
        except ImportError as exc:
            raise NativeModuleError(load_failure_message(exc)) from exc
        _core = module
    return _core


def available_presets():
    """Preset names of the solver, or the documented list if it cannot load."""
    try:
        return tuple(core().PRESETS)
    except NativeModuleError:
        return FALLBACK_PRESETS
