"""The style-slot list and custom-normal operators behind the panel's buttons."""

import bpy
import pytest

import helpers


def _names(obj):
    return [slot.name for slot in obj.gauss_stylization.styles]


def test_add_move_remove_slots():
    obj = helpers.suzanne(levels=0)
    for _ in range(3):
        assert bpy.ops.object.gauss_style_add() == {'FINISHED'}
    settings = obj.gauss_stylization
    assert _names(obj) == ["Style 1", "Style 2", "Style 3"] and settings.active_style_index == 2
    bpy.ops.object.gauss_style_move(direction='UP')
    assert _names(obj) == ["Style 1", "Style 3", "Style 2"] and settings.active_style_index == 1
    settings.active_style_index = 0
    assert bpy.ops.object.gauss_style_move(direction='UP') == {'CANCELLED'}  # already first
    bpy.ops.object.gauss_style_remove()
    assert _names(obj) == ["Style 3", "Style 2"] and settings.active_style_index == 0


def test_custom_normal_buttons():
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, 'CUBE')
    with pytest.raises(RuntimeError, match="not set to Custom"):
        bpy.ops.object.gauss_normal_add()
    slot.preset = 'CUSTOM'
    bpy.ops.object.gauss_normal_add()
    bpy.ops.object.gauss_normal_add()
    assert slot.custom_normal_list() == [(0, 0, 1), (0, 0, 1)]
    bpy.ops.object.gauss_normal_remove()
    assert len(slot.custom_normals) == 1


def test_normals_from_selected_faces():
    bpy.ops.mesh.primitive_cube_add()
    obj = bpy.context.active_object
    slot = helpers.add_slot(obj, 'CUSTOM')
    with pytest.raises(RuntimeError, match="No faces are selected"):
        for polygon in obj.data.polygons:
            polygon.select = False
        bpy.ops.object.gauss_normals_from_faces()
    for polygon in obj.data.polygons:
        polygon.select = polygon.normal.z > 0.5 or polygon.normal.x > 0.5
    assert bpy.ops.object.gauss_normals_from_faces() == {'FINISHED'}
    assert sorted(slot.custom_normal_list()) == [(0, 0, 1), (1, 0, 0)]
