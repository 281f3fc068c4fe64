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


_core = None


def core():
    """Return the ``gauss_core`` module or raise NativeModuleError."""
    global _core
    if _core is None:
        try:
            from . import gauss_core as module
        except ImportError as exc:
            version = "%d.%d" % sys.version_info[:2]
            raise NativeModuleError(
                "The Gauss solver (gauss_core native module) is missing or was built for "
                "another Python (Blender runs Python %s; the module must be built for it): %s"
                % (version, exc)) from exc
        _core = module
    return _core


def available_presets():
    """Preset names of the solver, or the documented list if it cannot load."""
    try:
        return tuple(core().PRESETS)
    except NativeModuleError:
        return FALLBACK_PRESETS
