"""Checks done before the solver sees anything, with messages for artists.

Every check raises ``SettingsError``; the operators turn it into an error
report and leave the mesh untouched. The settings' own checks (ranges,
vertex groups, custom normals) come with their fields (fields.py, schema.py).
"""

import numpy as np

from ..errors import SettingsError
from . import schema
from .fields import Where, check_all


def object_problem(context, need_mesh=True):
    """Why the stylize operators cannot run in ``context`` (None if they can).
    need_mesh: the active object itself must be a mesh."""
    obj = context.active_object
    if obj is None:
        return "Select a mesh object first"
    if need_mesh and obj.type != 'MESH':
        return "'%s' is not a mesh; select a mesh object" % obj.name
    if context.mode != 'OBJECT':
        return "Switch to Object Mode to stylize"
    return None


def inspect_problem(context):
    """Why an operator that looks at the active mesh (selects faces of it, measures it) cannot run (None
    if it can): it needs a mesh in Object Mode or Edit Mode, where a selection can be made and seen."""
    obj = context.active_object
    if obj is None or obj.type != 'MESH':
        return "Select a mesh object first"
    if obj.mode not in {'OBJECT', 'EDIT'}:
        return "Only in Object Mode or Edit Mode"
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


def check_pins(obj, pinned, triangles):
    """A run where every vertex a face uses is pinned cannot move anything: say so instead of
    running steps that change nothing. pinned: (#P,) vertex indices; triangles: (#T,3)."""
    if len(pinned) == 0 or len(triangles) == 0:
        return
    held = np.zeros(int(triangles.max()) + 1, bool)
    held[pinned[pinned < len(held)]] = True
    if held[triangles].all():
        raise SettingsError("Every vertex of '%s' is in the Pin Group '%s', so nothing can move; "
                            "take some vertices out of the group or clear Pin Group"
                            % (obj.name, obj.gauss_stylization.pin_group))


def check_settings(obj, settings, known_groups):
    """All settings of ``obj`` against the vertex groups read at start ({name: weights})."""
    check_all(schema.OBJECT, settings, Where(obj, known_groups))


def poll_result(cls, problem):
    """Operator poll helper: show ``problem`` in the tooltip when greyed out."""
    if problem is not None and hasattr(cls, "poll_message_set"):  # Blender >= 3.0
        cls.poll_message_set(problem)
    return problem is None
