"""Select Crossing Faces: the faces of the active mesh that pass through another, selected, so that
an artist checks a print before exporting it, with Avoid Self-Intersections or without. Select Held
Faces: during a live run, the faces where Avoid Self-Intersections holds the run back."""

import bpy

from . import native
from .errors import NativeModuleError
from .mesh import crossings
from .run import runs
from .settings.validation import inspect_problem, poll_result


def said(found):
    """What the operator reports: how many pairs cross and what it selected."""
    if not len(found.pairs):
        return "No faces cross each other"
    text = "%d pairs of faces cross each other; their %d faces are selected" % (len(found.pairs),
                                                                              len(found.polygons))
    if not found.shown:
        text += " (counted on the mesh under the modifiers, which change its faces)"
    return text


class OBJECT_OT_gauss_select_intersections(bpy.types.Operator):
    """Select the faces of the active mesh that pass through another face (counted as the 3D-Print
    toolbox counts them), to check a print before exporting it; Edit Mode shows them"""
    bl_idname = "object.gauss_select_intersections"
    bl_label = "Select Crossing Faces"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return poll_result(cls, inspect_problem(context))

    def execute(self, context):
        obj = context.active_object
        try:
            gauss_core = native.core()
        except NativeModuleError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        if obj.mode == 'EDIT':
            obj.update_from_editmode()
        try:
            found = crossings.find(gauss_core, obj, context.evaluated_depsgraph_get())
        except ValueError as exc:  # NaN or infinite coordinates
            self.report({'ERROR'}, "Cannot check '%s': %s" % (obj.name, exc))
            return {'CANCELLED'}
        crossings.select_and_show(context, obj, found.polygons, runs.is_running(obj))
        self.report({'WARNING'} if len(found.pairs) else {'INFO'}, said(found))
        return {'FINISHED'}


def _held_problem(context):
    problem = inspect_problem(context)
    if problem:
        return problem
    obj = context.active_object
    session = runs.session_of(obj)
    if session is None:
        return "Only while Stylize runs live on '%s'" % obj.name
    if not len(session.held_anywhere):
        return "Avoid Self-Intersections has held no vertex back in this run"
    if not session.plan.source.same_topology:
        return "The modifiers change the faces of '%s': its own faces cannot be selected" % obj.name
    return None


class OBJECT_OT_gauss_select_held(bpy.types.Operator):
    """Select the faces where Avoid Self-Intersections has held the live run back (those around every
    vertex it held in some step of the run); Edit Mode shows them once the run is kept"""
    bl_idname = "object.gauss_select_held"
    bl_label = "Select Held Faces"
    bl_options = {'INTERNAL'}  # not registered: a live run counts registered operators as edits

    @classmethod
    def poll(cls, context):
        return poll_result(cls, _held_problem(context))

    def execute(self, context):
        obj = context.active_object
        session = runs.session_of(obj)
        held = session.held_anywhere
        polygons = crossings.polygons_with_vertices(session.arrays, held)
        crossings.select_polygons(obj.data, polygons)
        self.report({'INFO'}, "Avoid Self-Intersections has held %d vertices back in this run; their %d faces "
                    "are selected" % (len(held), len(polygons)))
        return {'FINISHED'}


classes = (OBJECT_OT_gauss_select_intersections, OBJECT_OT_gauss_select_held)
