"""Operators that edit the list of style slots and their custom normals."""

import bpy
from bpy.props import EnumProperty

from .schema import CUSTOM
from .validation import poll_result


def _settings(context):
    obj = context.object
    return obj.gauss_stylization if obj is not None and obj.type == 'MESH' else None


def _append(owner, collection, index_attr):
    """Add an item to a UI list's collection and make it the active one."""
    item = collection.add()
    setattr(owner, index_attr, len(collection) - 1)
    return item


def _remove_active(owner, collection, index_attr):
    """Remove a UI list's active item; the next one (or the new last one) becomes active."""
    index = getattr(owner, index_attr)
    if not 0 <= index < len(collection):
        return {'CANCELLED'}
    collection.remove(index)
    setattr(owner, index_attr, min(index, len(collection) - 1))
    return {'FINISHED'}


class _SlotOperator:
    bl_options = {'REGISTER', 'UNDO', 'INTERNAL'}

    @classmethod
    def poll(cls, context):
        return poll_result(cls, None if _settings(context) is not None else "Select a mesh object first")


class OBJECT_OT_gauss_style_add(_SlotOperator, bpy.types.Operator):
    """Add a style slot (assign it a vertex group to style only that region)"""
    bl_idname = "object.gauss_style_add"
    bl_label = "Add Style"

    def execute(self, context):
        settings = _settings(context)
        slot = _append(settings, settings.styles, "active_style_index")
        slot.name = "Style %d" % len(settings.styles)
        return {'FINISHED'}


class OBJECT_OT_gauss_style_remove(_SlotOperator, bpy.types.Operator):
    """Remove the active style slot"""
    bl_idname = "object.gauss_style_remove"
    bl_label = "Remove Style"

    def execute(self, context):
        settings = _settings(context)
        return _remove_active(settings, settings.styles, "active_style_index")


class OBJECT_OT_gauss_style_move(_SlotOperator, bpy.types.Operator):
    """Move the active style slot (later slots win where regions overlap)"""
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
        return {'FINISHED'}


def _active_custom_slot(context):
    settings = _settings(context)
    if settings is None or not 0 <= settings.active_style_index < len(settings.styles):
        return None
    slot = settings.styles[settings.active_style_index]
    return slot if slot.preset == CUSTOM else None


class _NormalOperator(_SlotOperator):
    @classmethod
    def poll(cls, context):
        return poll_result(cls, None if _active_custom_slot(context) is not None
                           else "The active style slot is not set to Custom")


class OBJECT_OT_gauss_normal_add(_NormalOperator, bpy.types.Operator):
    """Add a preferred normal to the active custom style"""
    bl_idname = "object.gauss_normal_add"
    bl_label = "Add Normal"

    def execute(self, context):
        slot = _active_custom_slot(context)
        _append(slot, slot.custom_normals, "active_normal_index").vector = (0.0, 0.0, 1.0)
        return {'FINISHED'}


class OBJECT_OT_gauss_normal_remove(_NormalOperator, bpy.types.Operator):
    """Remove the active normal of the active custom style"""
    bl_idname = "object.gauss_normal_remove"
    bl_label = "Remove Normal"

    def execute(self, context):
        slot = _active_custom_slot(context)
        return _remove_active(slot, slot.custom_normals, "active_normal_index")


class OBJECT_OT_gauss_normals_from_faces(_NormalOperator, bpy.types.Operator):
    """Add the normals of the faces selected in Edit Mode to the active custom style"""
    bl_idname = "object.gauss_normals_from_faces"
    bl_label = "From Selected Faces"

    def execute(self, context):
        mesh = context.object.data
        # One entry per distinct direction; degenerate faces have no usable normal.
        normals = sorted({tuple(round(x, 4) for x in p.normal)
                          for p in mesh.polygons if p.select and p.normal.length > 0.5})
        if not normals:
            self.report({'ERROR'}, "No faces are selected: select faces in Edit Mode, then come back")
            return {'CANCELLED'}
        slot = _active_custom_slot(context)
        slot.set_custom_normals(slot.custom_normal_list() + normals)
        return {'FINISHED'}


classes = (
    OBJECT_OT_gauss_style_add, OBJECT_OT_gauss_style_remove, OBJECT_OT_gauss_style_move,
    OBJECT_OT_gauss_normal_add, OBJECT_OT_gauss_normal_remove, OBJECT_OT_gauss_normals_from_faces,
)
