"""Checks done before the solver sees anything, with messages for artists.

Every check raises ``SettingsError``; the operators turn it into an error
report and leave the mesh untouched.
"""

import math

import numpy as np

from . import native
from .properties import CUSTOM


class SettingsError(ValueError):
    """A setting or the mesh cannot be stylized; the message is shown to the artist."""


def object_problem(context):
    """Why the stylize operators cannot run in ``context`` (None if they can)."""
    obj = context.active_object
    if obj is None:
        return "Select a mesh object first"
    if obj.type != 'MESH':
        return "'%s' is not a mesh; select a mesh object" % obj.name
    if context.mode != 'OBJECT':
        return "Switch to Object Mode to stylize"
    return None


def check_object(obj):
    mesh = obj.data
    if mesh.library is not None or getattr(mesh, "override_library", None) is not None:
        raise SettingsError("Mesh '%s' is linked from another file and cannot be changed" % mesh.name)
    if len(mesh.vertices) == 0:
        raise SettingsError("'%s' has no vertices to stylize" % obj.name)
    if len(mesh.polygons) == 0:
        raise SettingsError("'%s' has no faces to stylize (only loose vertices or edges)" % obj.name)


def check_coordinates(obj, coords):
    if not np.isfinite(coords).all():
        raise SettingsError("'%s' has broken vertex positions (NaN or infinite); "
                            "fix or delete those vertices first" % obj.name)


def _number(value, what, low, high):
    if not (math.isfinite(value) and low <= value <= high):
        raise SettingsError("%s must be a number between %g and %g (it is %s)" % (what, low, high, value))


def _check_group(group, known_groups, what, obj):
    if not group or group in known_groups:
        return
    if group in obj.vertex_groups:  # weights are read once, when stylization starts
        raise SettingsError("%s: vertex group '%s' was added after Stylize started; "
                            "restart Stylize to use it" % (what, group))
    raise SettingsError("%s: there is no vertex group '%s' on '%s'" % (what, group, obj.name))


def check_slot(slot, known_groups, obj, presets):
    what = "Style '%s'" % slot.name
    _number(slot.sigma, what + ": Sigma", 1e-6, 1000.0)
    _number(slot.mu, what + ": Mu", 0.0, 1000.0)
    _number(slot.axis_contribution, what + ": Axis Contribution", 0.0, 1.0)
    if not all(math.isfinite(a) for a in slot.orientation):
        raise SettingsError(what + ": Orientation must be finite angles")
    _check_group(slot.vertex_group, known_groups, what, obj)
    if slot.preset == CUSTOM:
        _check_custom_normals(slot, what)
    elif slot.preset.lower() not in presets:
        raise SettingsError("%s: the solver has no '%s' style; pick another one" % (what, slot.preset))


def _check_custom_normals(slot, what):
    normals = slot.custom_normal_list()
    if not normals:
        raise SettingsError(what + " is set to Custom but has no normals; add at least one")
    for number, normal in enumerate(normals, 1):
        if not all(math.isfinite(x) for x in normal):
            raise SettingsError("%s: custom normal %d is not a finite vector" % (what, number))
        if sum(x * x for x in normal) < 1e-12:
            raise SettingsError("%s: custom normal %d has zero length" % (what, number))


def check_settings(obj, settings, known_groups):
    """All settings of ``obj`` against the vertex groups read at start."""
    _number(settings.lam, "Lambda", 0.0, 1.0e4)
    if not 1 <= settings.admm_iterations <= 100:
        raise SettingsError("ADMM Iterations must be between 1 and 100")
    _check_group(settings.pin_group, known_groups, "Pin Group", obj)
    presets = native.core().PRESETS
    for slot in settings.styles:
        check_slot(slot, known_groups, obj, presets)


def poll_result(cls, problem):
    """Operator poll helper: show ``problem`` in the tooltip when greyed out."""
    if problem is not None and hasattr(cls, "poll_message_set"):  # Blender >= 3.0
        cls.poll_message_set(problem)
    return problem is None
