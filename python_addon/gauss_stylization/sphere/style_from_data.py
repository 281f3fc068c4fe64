"""Styles from data: a Custom style taken from an example object's face directions,
and the rotation of a style that the mesh, as it is, already fits best."""

import bpy
import numpy as np
from bpy.props import IntProperty, StringProperty
from mathutils import Matrix

from .. import native
from ..errors import NativeModuleError, SettingsError
from ..settings import schema, settings_io, styles
from ..settings.validation import poll_result
from ..view.viewport import redraw_sidebars
from . import directions, orientation, surface

MAX_DIRECTIONS = 32  # default number of directions taken from an example


def _mesh_object(context):
    obj = context.active_object
    return obj if obj is not None and obj.type == 'MESH' else None


def _mesh_problem(context):
    return None if _mesh_object(context) is not None else "Select a mesh object first"


def _slot_problem(context):
    """Why Auto Orient cannot run on the (mesh) active object's slots, or None."""
    if styles.active_slot(context.active_object.gauss_stylization) is None:
        return "Add a style slot first"
    return None


def _core(operator):
    try:
        return native.core()
    except NativeModuleError as exc:
        operator.report({'ERROR'}, str(exc))
        return None


def example_directions(gauss_core, source, target, depsgraph, max_directions):
    """The dominant face directions of ``source`` (as displayed) in ``target``'s object
    space: (directions D by 3, shares of the area D). Turned by the two objects'
    rotations (their scales are left out: a direction is a direction)."""
    normals, areas = surface.evaluated_face_normals(source, depsgraph)
    found, shares = directions.dominant_directions(gauss_core, normals, areas, max_directions)
    return _into_target(found, source, target), shares


def _into_target(found, source, target):
    """Directions in ``source``'s object space turned into ``target``'s."""
    into_target = surface.world_rotation(target).T @ surface.world_rotation(source)
    return found @ into_target.T


def _pick_example(operator, context):
    """invoke() of the operators that take a style from an example object: the example is the other
    selected mesh unless one is named, asked for in a dialog."""
    if not operator.source:
        others = [o for o in context.selected_objects if o.type == 'MESH' and o != context.active_object]
        operator.source = others[0].name if others else ""
    return context.window_manager.invoke_props_dialog(operator)


def _example(operator):
    """The example object ``operator.source`` names, or None (reported) when it names no mesh."""
    source = bpy.data.objects.get(operator.source)
    if source is None or source.type != 'MESH':
        operator.report({'ERROR'}, "Choose a mesh object as the example (%s)"
                        % ("'%s' is not a mesh" % operator.source if source else
                           "there is no object '%s'" % operator.source if operator.source else "none chosen"))
        return None
    return source


# Each operator below defines poll, invoke and draw itself and calls the helpers above: with them
# inherited from one shared base class, neither operator's dialog opened in a real window (execute ran at
# once, with no example chosen; the windowed drivers windowed_panel.py and windowed_live_run.py).
class OBJECT_OT_gauss_style_from_object(bpy.types.Operator):
    """Add a Custom style whose preferred normals are the dominant face directions of
    another mesh object (e.g. a low-poly example)"""
    bl_idname = "object.gauss_style_from_object"
    bl_label = "From Object"
    bl_options = {'REGISTER', 'UNDO'}

    source: StringProperty(name="Example", description="Mesh object whose face directions become the style")
    max_directions: IntProperty(
        name="Max Directions", default=MAX_DIRECTIONS, min=1, max=256,
        description="Keep at most this many directions (those covering the most area); clusters of "
                    "face normals with less than %g%% of the area are always dropped" % (directions.MIN_SHARE * 100))

    @classmethod
    def poll(cls, context):
        return poll_result(cls, _mesh_problem(context))

    def invoke(self, context, event):
        return _pick_example(self, context)

    def draw(self, context):
        self.layout.prop_search(self, "source", context.scene, "objects", icon='OBJECT_DATA')
        self.layout.prop(self, "max_directions")

    def execute(self, context):
        obj = context.active_object
        source = _example(self)
        if source is None:
            return {'CANCELLED'}
        gauss_core = _core(self)
        if gauss_core is None:
            return {'CANCELLED'}
        found, shares = example_directions(gauss_core, source, obj, context.evaluated_depsgraph_get(),
                                           self.max_directions)
        if not len(found):
            self.report({'ERROR'}, "'%s' has no faces with area to take directions from" % source.name)
            return {'CANCELLED'}
        settings = obj.gauss_stylization
        settings_io.add_slot(settings, {"name": "From %s" % source.name, "preset": schema.CUSTOM,
                                        "custom_normals": found.tolist()})
        settings.active_style_index = len(settings.styles) - 1
        self.report({'INFO'}, "Added a style with %d directions from '%s' (they cover %.0f%% of its area)"
                    % (len(found), source.name, 100.0 * shares.sum()))
        redraw_sidebars(context)
        return {'FINISHED'}


def example_gauss_map(source, target, depsgraph):
    """The whole Gauss map of ``source`` (as displayed) in ``target``'s object space: (directions M by 3,
    area shares M), turned as example_directions turns them (directions.gauss_map)."""
    normals, areas = surface.evaluated_face_normals(source, depsgraph)
    found, shares = directions.gauss_map(normals, areas)
    return _into_target(found, source, target), shares


class OBJECT_OT_gauss_style_from_gauss_map(bpy.types.Operator):
    """Add a Gauss Map style: the whole normal distribution of another mesh object (e.g. a low-poly
    example); each face turns towards the example's nearest face direction"""
    bl_idname = "object.gauss_style_from_gauss_map"
    bl_label = "From Gauss Map"
    bl_options = {'REGISTER', 'UNDO'}

    source: StringProperty(name="Example", description="Mesh object whose normal distribution becomes the style")

    @classmethod
    def poll(cls, context):
        return poll_result(cls, _mesh_problem(context))

    def invoke(self, context, event):
        return _pick_example(self, context)

    def draw(self, context):
        self.layout.prop_search(self, "source", context.scene, "objects", icon='OBJECT_DATA')

    def execute(self, context):
        obj = context.active_object
        source = _example(self)
        if source is None:
            return {'CANCELLED'}
        if _core(self) is None:
            return {'CANCELLED'}
        found, shares = example_gauss_map(source, obj, context.evaluated_depsgraph_get())
        if not len(found):
            self.report({'ERROR'}, "'%s' has no faces with area to take a Gauss map from" % source.name)
            return {'CANCELLED'}
        settings = obj.gauss_stylization
        settings_io.add_slot(settings, {"name": "Gauss Map of %s" % source.name, "preset": schema.GAUSS_MAP,
                                        "gauss_map": np.column_stack([found, shares]).tolist()})
        settings.active_style_index = len(settings.styles) - 1
        self.report({'INFO'}, "Added a Gauss Map style from '%s' (%d directions)" % (source.name, len(found)))
        redraw_sidebars(context)
        return {'FINISHED'}


class OBJECT_OT_gauss_style_auto_orient(bpy.types.Operator):
    """Set the active style's rotation to the one under which the mesh, as it is, already
    fits the style best (the smallest such rotation when several fit equally well)"""
    bl_idname = "object.gauss_style_auto_orient"
    bl_label = "Auto Orient"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return poll_result(cls, _mesh_problem(context) or _slot_problem(context))

    def execute(self, context):
        obj = context.active_object
        slot = styles.active_slot(obj.gauss_stylization)
        gauss_core = _core(self)
        if gauss_core is None:
            return {'CANCELLED'}
        try:
            style = styles.checked_style(gauss_core, obj, slot, rotation=np.eye(3))
            search = styles.checked_style(gauss_core, obj, slot, rotation=np.eye(3),
                                          sigma=min(slot.sigma, orientation.SEARCH_SIGMA))
        except SettingsError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        normals, areas = surface.face_normals(obj)
        if not (areas > 0).any():
            self.report({'ERROR'}, "'%s' has no faces with area to fit the style to" % obj.name)
            return {'CANCELLED'}
        rotation, fit = orientation.best_rotation(style, normals, areas, search)
        slot.orientation = Matrix(rotation.tolist()).to_euler('XYZ')
        self.report({'INFO'}, "Style '%s' turned %s (object axes); the mesh fits it with mean g %.3f"
                    % (slot.name, orientation.rotation_in_words(rotation), fit))
        redraw_sidebars(context)
        return {'FINISHED'}


classes = (OBJECT_OT_gauss_style_from_object, OBJECT_OT_gauss_style_from_gauss_map,
           OBJECT_OT_gauss_style_auto_orient)
