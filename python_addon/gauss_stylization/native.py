"""Access to the compiled solver module ``gauss_core`` and to the facts it owns.

The add-on must register (and show its panel) even when the native module is
missing or was built for another Python, so that the artist sees a readable
message instead of a traceback. Everything that needs the solver calls
``core()``, which raises ``NativeModuleError`` with that message.

The solver owns the defaults and hard limits of its settings and the preset
registry. ``facts()`` returns them from ``gauss_core``, or, when it cannot be
imported, from ``core_facts.json``, which the build writes next to this file
from the same table (cpp/include/gauss/settings.h), so the properties register
with the same defaults, ranges and preset numbers either way.
"""

import functools
import json
import os
import sys
from collections import namedtuple

from .errors import NativeModuleError

FACTS_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "core_facts.json")

# defaults: {name: value} (also "preset": the default preset name);
# limits:   {name: (min, max)}, inclusive;
# presets:  preset names; the position of each is its enum number in saved .blend files.
# methods:  stylization method names ("gauss", "cubic"), numbered the same way.
# sizes:    {"normals": .., "rings": ..}: the most a style takes (settings.h).
Facts = namedtuple("Facts", "defaults limits presets methods sizes")

def load_failure_message(exc):
    """What the artist reads when ``gauss_core`` cannot be imported: why, and which build fixes it.

    A module only loads in the Python version it was built for (its file name says which:
    gauss_core.cpython-311-x86_64-linux-gnu.so is for 3.11) and on a glibc at least as new as the
    one it needs, so the message names the Python, numpy and glibc this Blender runs and the
    modules the add-on folder holds (README: "Which Blender can load this build").
    """
    import platform
    import re
    try:
        import numpy
        numpy_version = numpy.__version__
    except ImportError:
        numpy_version = "none importable"
    libc, libc_version = platform.libc_ver()
    python = "%d.%d" % sys.version_info[:2]
    found = {}  # file name -> the Python it was built for
    for path in bundled_modules():
        built_for = re.search(r"\.cpython-(\d)(\d+)-", os.path.basename(path))
        found[os.path.basename(path)] = "%s.%s" % built_for.groups() if built_for else "unknown"
    if not found and not isinstance(exc, ModuleNotFoundError):
        problem = ("the gauss_core module installed for it (from the extension's wheel) does not load "
                   "here")
        fix = ("install the extension zip built for Python %s and this platform (its name has -cp%d%d-), "
               "and numpy as Blender bundles it" % (python, sys.version_info[0], sys.version_info[1]))
    elif python in found.values():
        problem = "the module for Python %s is there but does not load on this system" % python
        fix = ("build the module on this machine (a GLIBC version in the import error means this "
               "system's glibc is older than the module needs; a numpy version, that the module was built "
               "with a pybind11 that cannot read this numpy)")
    else:
        problem = ("this add-on only holds " + ", ".join(
            "a module for Python %s (%s)" % (v, name) for name, v in found.items())
            if found else "this add-on holds no gauss_core module at all, and none is installed from an "
            "extension's wheel")
        fix = ("install the add-on zip built for Python %s (its name ends in -cp%d%d-linux_x86_64.zip; "
               "in Blender 4.2 and later the extension zip with -cp%d%d- in its name) or build one against "
               "a Python %s" % (python, sys.version_info[0], sys.version_info[1], sys.version_info[0],
                                sys.version_info[1], python))
    return ("The Gauss solver (gauss_core native module) cannot load: Blender runs Python %s with "
            "numpy %s on %s %s, and %s. Fix: %s; see the README, \"Which Blender can load this "
            "build\". (%s: %s)" % (platform.python_version(), numpy_version, libc or "a C library",
                                    libc_version or "of unknown version", problem, fix,
                                    type(exc).__name__, exc))


_core = None
_facts = None
_ring_presets = None


def bundled_modules():
    """The gauss_core files in the add-on's own folder (the classic zip bundles one)."""
    import glob
    folder = os.path.dirname(os.path.abspath(__file__))
    return sorted(glob.glob(os.path.join(folder, "gauss_core*")))


def import_gauss_core():
    """The solver module, found the way this add-on was installed.

    A classic zip bundles it in the add-on folder: then only that copy is used, so that a top-level
    gauss_core of another build (e.g. an extension's wheel for another version) cannot shadow it. An
    extension ships it as a wheel, which Blender installs as a top-level module.
    """
    if bundled_modules():
        from . import gauss_core as module
    else:
        import gauss_core as module
    return module


def core():
    """Return the ``gauss_core`` module or raise NativeModuleError."""
    global _core
    if _core is None:
        try:
            module = import_gauss_core()
        except Exception as exc:  # noqa: BLE001 - a module's init may raise anything; Blender must not fail
            # ImportError (wrong Python, missing file, a numpy it cannot read: the module refuses to
            # load), OSError or SystemError from the loader: all of them mean "cannot load".
            raise NativeModuleError(load_failure_message(exc)) from exc
        _core = module
    return _core


def facts():
    """The solver's DEFAULTS, LIMITS and PRESETS, from the module or its JSON copy."""
    global _facts
    if _facts is None:
        try:
            module = core()
        except NativeModuleError as exc:
            _facts = read_facts_file(FACTS_FILE, exc)
        else:
            _facts = _checked_facts(module.DEFAULTS, module.LIMITS, module.PRESETS, module.METHODS,
                                    module.SIZE_LIMITS)
    return _facts


def ring_presets():
    """Names of the solver's presets whose style has rings of preferred normals (where a style's
    axis_contribution acts), asked from the solver itself; None when the module cannot load."""
    global _ring_presets
    if _ring_presets is None:
        try:
            module = core()
        except NativeModuleError:
            return None
        _ring_presets = frozenset(name for name in module.PRESETS if len(module.Style.preset(name).ring_offsets))
    return _ring_presets


def preset_strengths():
    """{preset name: (its own sigma, the lambda it is meant for)} of the presets that run at a lambda of
    their own (gauss_core.PRESET_LAMBDA: Sheet Metal), asked from the solver; {} when it cannot load."""
    try:
        module = core()
    except NativeModuleError:
        return {}
    return {name: (module.Style.preset(name).sigma, lam) for name, lam in module.PRESET_LAMBDA.items()}


@functools.lru_cache(maxsize=256)
def preset_takes_trust_region_step(name, sigma):
    """Does a face of preset ``name`` (a solver preset name) at ``sigma`` take the solver's trust-region
    normal step instead of the paper's (gauss_core.Style.trust_region_step; the option
    paper_step_any_sigma keeps the paper's)? None when the module cannot load."""
    try:
        module = core()
    except NativeModuleError:
        return None
    return bool(module.Style.preset(name, sigma=sigma).trust_region_step)


def paper_step_max_sigma():
    """The sigma up to which every style takes the paper's normal step (gauss_core.PAPER_STEP_MAX_SIGMA);
    None when the module cannot load."""
    try:
        return float(core().PAPER_STEP_MAX_SIGMA)
    except NativeModuleError:
        return None


def read_facts_file(path, import_error=None):
    """Facts from a core_facts.json (keys DEFAULTS, LIMITS, PRESETS, METHODS, SIZE_LIMITS)."""
    try:
        with open(path, encoding="utf-8") as handle:
            data = json.load(handle)
        return _checked_facts(data["DEFAULTS"], data["LIMITS"], data["PRESETS"], data["METHODS"],
                              data["SIZE_LIMITS"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise NativeModuleError(
            "The add-on cannot read the solver's settings: %s, and %s is unreadable (%s). "
            "Reinstall the add-on from a complete build." % (import_error or "no gauss_core module",
                                                             path, exc)) from exc


def _checked_facts(defaults, limits, presets, methods, sizes):
    limits = {name: (low, high) for name, (low, high) in dict(limits).items()}
    presets = tuple(str(name) for name in presets)
    methods = tuple(str(name) for name in methods)
    defaults = dict(defaults)
    sizes = {name: int(value) for name, value in dict(sizes).items()}
    if (not presets or defaults.get("preset") not in presets or defaults.get("method") not in methods
            or not set(limits) <= set(defaults) or set(sizes) != {"normals", "rings"}):
        raise ValueError("inconsistent solver facts (defaults %r, limits %r, presets %r, methods %r, sizes %r)"
                         % (defaults, limits, presets, methods, sizes))
    return Facts(defaults, limits, presets, methods, sizes)
