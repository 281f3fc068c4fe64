"""The style-slot list and custom-normal operators behind the panel's buttons."""

import bpy
import pytest

import helpers


def _names(obj):
    return [slot.name for slot in obj.gauss_stylization.styles]


def test_add_move_remove_slots():
    obj = helpers.suzanne(levels=0)
    settings = obj.gauss_stylization
    for preset in ('CUBE', 'OCTAHEDRON', 'TETRAHEDRON'):
        assert bpy.ops.object.gauss_style_add() == {'FINISHED'}
        settings.styles[-1].preset = preset
    assert _names(obj) == ["Cube", "Octahedron", "Tetrahedron"] and settings.active_style_index == 2
    bpy.ops.object.gauss_style_move(direction='UP')
    assert _names(obj) == ["Cube", "Tetrahedron", "Octahedron"] and settings.active_style_index == 1
    settings.active_style_index = 0
    assert bpy.ops.object.gauss_style_move(direction='UP') == {'CANCELLED'}  # already first
    bpy.ops.object.gauss_style_remove()
    assert _names(obj) == ["Tetrahedron", "Octahedron"] and settings.active_style_index == 0


def test_a_slot_is_named_after_its_style_until_the_artist_renames_it():
    obj = helpers.suzanne(levels=0)
    bpy.ops.object.gauss_style_add()
    slot = obj.gauss_stylization.styles[0]
    assert slot.name == "Cube"
    slot.preset = 'OCTAHEDRON'
    assert slot.name == "Octahedron"
    slot.preset = 'CUSTOM'
    assert slot.name == "Custom"
    slot.name = "Ears"
    slot.preset = 'CUBE'
    assert slot.name == "Ears"


def test_a_saved_name_survives_loading_with_its_style(addon):
    """Settings are written name after Style, so a name that happens to be another style's stays."""
    obj = helpers.suzanne(levels=0)
    helpers.settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"name": "Cube", "preset": 'OCTAHEDRON'}]})
    assert _names(obj) == ["Cube"]


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


def _select_in_edit_mode(obj, select):
    """Select the faces for which ``select(normal)`` holds, in Edit Mode's own mesh (as clicking
    them would); the object's mesh data only learn of it when Edit Mode is left."""
    import bmesh
    bm = bmesh.from_edit_mesh(obj.data)
    for face in bm.faces:
        face.select_set(select(face.normal))
    bmesh.update_edit_mesh(obj.data)


def test_from_selected_faces_reads_the_live_edit_mode_selection(capfd):
    # In Edit Mode the mesh data's selection is stale; reading it would say "No faces are selected".
    bpy.ops.mesh.primitive_cube_add()
    obj = bpy.context.active_object
    slot = helpers.add_slot(obj, 'CUSTOM')
    bpy.ops.object.mode_set(mode='EDIT')
    try:
        _select_in_edit_mode(obj, lambda n: n.z > 0.5 or n.y < -0.5)
        assert bpy.ops.object.gauss_normals_from_faces() == {'FINISHED'}
        assert sorted(slot.custom_normal_list()) == [(0, -1, 0), (0, 0, 1)]
        _select_in_edit_mode(obj, lambda n: n.x < -0.5)  # another selection, still in Edit Mode
        slot.set_custom_normals([(1, 1, 1)])
        assert bpy.ops.object.gauss_normals_from_faces() == {'FINISHED'}
        assert slot.custom_normal_list()[1:] == [(-1, 0, 0)]
    finally:
        bpy.ops.object.mode_set(mode='OBJECT')
    assert "Added 1 direction from 1 face" in capfd.readouterr().out


def test_from_selected_faces_merges_near_parallel_faces_and_says_how_many(capfd):
    obj = helpers.suzanne(levels=0)
    bpy.ops.object.mode_set(mode='OBJECT')
    slot = helpers.add_slot(obj, 'CUSTOM')
    for polygon in obj.data.polygons:
        polygon.select = True
    capfd.readouterr()
    assert bpy.ops.object.gauss_normals_from_faces() == {'FINISHED'}
    merged = len(slot.custom_normals)
    assert 0 < merged < len(obj.data.polygons)
    assert "Added %d directions from 500 faces" % merged in capfd.readouterr().out
    slot.set_custom_normals([(0, 0, 1)])
    assert bpy.ops.object.gauss_normals_from_faces(merge_angle=0.0) == {'FINISHED'}
    assert len(slot.custom_normals) - 1 > merged  # no merging: (almost) one direction per face
