"""Operators that edit the list of style slots and their custom normals.

Both lists work alike: a collection, its owner and the owner's active index.
``_StyleList`` and ``_NormalList`` say which list an operator edits (and when
it can), ``_AddItem`` and ``_RemoveActive`` what it does to it.
"""

import math

import bpy
from bpy.props import EnumProperty, FloatProperty

from . import native
from .errors import NativeModuleError
from .mesh.mesh_io import read_selected_faces
from .settings.schema import CUSTOM, style_label
from .settings.styles import active_slot
from .settings.validation import poll_result
from .view.viewport import redraw_sidebars


def _settings(context):
    obj = context.object
    return obj.gauss_stylization if obj is not None and obj.type == 'MESH' else None


def _active_custom_slot(context):
    settings = _settings(context)
    slot = None if settings is None else active_slot(settings)
    return slot if slot is not None and slot.preset == CUSTOM else None


class _StyleList:
    bl_options = {'REGISTER', 'UNDO', 'INTERNAL'}

    @classmethod
    def poll(cls, context):
        return poll_result(cls, None if _settings(context) is not None else "Select a mesh object first")

    @staticmethod
    def edited_list(context):
        """(owner, collection, name of the owner's active-index property)"""
        settings = _settings(context)
        return settings, settings.styles, "active_style_index"


class _NormalList(_StyleList):
    @classmethod
    def poll(cls, context):
        return poll_result(cls, None if _active_custom_slot(context) is not None
                           else "The active style slot is not set to Custom")

    @staticmethod
    def edited_list(context):
        slot = _active_custom_slot(context)
        return slot, slot.custom_normals, "active_normal_index"


class _AddItem:
    """Add an item (with its defaults) and make it the active one."""

    def execute(self, context):
        owner, collection, index_name = self.edited_list(context)
        item = collection.add()
        setattr(owner, index_name, len(collection) - 1)
        self.name_item(item, len(collection))
        redraw_sidebars(context)
        return {'FINISHED'}

    def name_item(self, item, count):
        """Items keep their default name unless the list says otherwise."""


class _RemoveActive:
    """Remove the active item; the next one (or the new last one) becomes active."""

    def execute(self, context):
        owner, collection, index_name = self.edited_list(context)
        index = getattr(owner, index_name)
        if not 0 <= index < len(collection):
            return {'CANCELLED'}
        collection.remove(index)
        setattr(owner, index_name, min(index, len(collection) - 1))
        redraw_sidebars(context)
        return {'FINISHED'}


class OBJECT_OT_gauss_style_add(_StyleList, _AddItem, bpy.types.Operator):
    """Add a style slot (assign it a vertex group to style only that region)"""
    bl_idname = "object.gauss_style_add"
    bl_label = "Add Style"

    def name_item(self, slot, count):
        slot.name = style_label(slot.preset)  # called after its style until renamed (schema.py)


class OBJECT_OT_gauss_style_remove(_StyleList, _RemoveActive, bpy.types.Operator):
    """Remove the active style slot"""
    bl_idname = "object.gauss_style_remove"
    bl_label = "Remove Style"


class OBJECT_OT_gauss_style_move(_StyleList, bpy.types.Operator):
    """Move the active style slot (the last slot without a Region fills what the Regions leave)"""
    bl_idname = "object.gauss_style_move"
    bl_label = "Move Style"

    direction: EnumProperty(items=(('UP', "Up", ""), ('DOWN', "Down", "")))

    def execute(self, context):
        settings = _settings(context)
        index = settings.active_style_index
        target = index - 1 if self.direction == 'UP' else index + 1
        if not (0 <= index < len(settings.styles) and 0 <= target < len(settings.styles)):
            return {'CANCELLED'}
        settings.styles.move(index, target)
        settings.active_style_index = target
        redraw_sidebars(context)
        return {'FINISHED'}


class OBJECT_OT_gauss_normal_add(_NormalList, _AddItem, bpy.types.Operator):
    """Add a preferred normal to the active custom style"""
    bl_idname = "object.gauss_normal_add"
    bl_label = "Add Normal"


class OBJECT_OT_gauss_normal_remove(_NormalList, _RemoveActive, bpy.types.Operator):
    """Remove the active normal of the active custom style"""
    bl_idname = "object.gauss_normal_remove"
    bl_label = "Remove Normal"


class OBJECT_OT_gauss_normals_from_faces(_NormalList, bpy.types.Operator):
    """Add the directions of the selected faces to the active custom style (faces with
    near-parallel normals give one direction, their area-weighted mean)"""
    bl_idname = "object.gauss_normals_from_faces"
    bl_label = "From Selected Faces"

    merge_angle: FloatProperty(
        name="Merge Angle", subtype='ANGLE', default=math.radians(5.0), min=0.0, max=math.radians(90.0),
        description="Faces whose normals lie within this angle of each other give one direction")

    def execute(self, context):
        obj = context.object
        normals, areas = read_selected_faces(obj)
        if len(normals) == 0:
            self.report({'ERROR'}, "No faces are selected: select faces in Edit Mode, then press this again")
            return {'CANCELLED'}
        try:
            directions, _weights = native.core().merge_directions(normals, math.degrees(self.merge_angle), areas)
        except (NativeModuleError, ValueError) as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        slot = _active_custom_slot(context)
        slot.set_custom_normals(slot.custom_normal_list() + [tuple(d) for d in directions.tolist()])
        self.report({'INFO'}, "Added {:,} direction{} from {:,} face{}".format(
            len(directions), "" if len(directions) == 1 else "s", len(normals), "" if len(normals) == 1 else "s"))
        redraw_sidebars(context)
        return {'FINISHED'}


class OBJECT_OT_gauss_paint_region(bpy.types.Operator):
    """Paint the active style's Region: Weight Paint mode with its vertex group the one painted, or,
    in Weight Paint, back to Object Mode. A live run holds the object still while it is painted and
    takes the strokes when it is back in Object Mode"""
    bl_idname = "object.gauss_paint_region"
    bl_label = "Paint Region"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        problem = None
        if _settings(context) is None:
            problem = "Select a mesh object"
        elif context.mode not in {'OBJECT', 'PAINT_WEIGHT'}:
            problem = "Only from Object Mode or Weight Paint"
        return poll_result(cls, problem)

    def execute(self, context):
        if context.mode == 'PAINT_WEIGHT':
            bpy.ops.object.mode_set(mode='OBJECT')
            return {'FINISHED'}
        obj = context.object
        slot = active_slot(obj.gauss_stylization)
        group = obj.vertex_groups.get(slot.vertex_group) if slot is not None and slot.vertex_group else None
        if group is not None:
            obj.vertex_groups.active_index = group.index
        else:
            self.report({'INFO'}, "The active style has no Region: strokes go to the active vertex group "
                                  "(pick a group as the style's Region to paint its strength)")
        bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
        return {'FINISHED'}


classes = (
    OBJECT_OT_gauss_style_add, OBJECT_OT_gauss_style_remove, OBJECT_OT_gauss_style_move,
    OBJECT_OT_gauss_normal_add, OBJECT_OT_gauss_normal_remove, OBJECT_OT_gauss_normals_from_faces,
    OBJECT_OT_gauss_paint_region,
)
