"""Scripted stylization (execute path): what an artist would see on the mesh."""

import bpy
import numpy as np

import helpers
from helpers import AXES

OCTAHEDRON = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)

# Measured with the solver (Nov 2025): subdivided Suzanne, cube preset, 100 steps:
# the area share within 10 degrees of an axis goes from 0.065 to 0.733.
MAX_SHARE_BEFORE = 0.15
MIN_CUBE_SHARE = 0.55


def test_cube_preset_aligns_suzanne_to_axes():
    obj = helpers.suzanne(levels=1)
    before = helpers.aligned_share(obj, AXES)
    assert helpers.stylize(100) == {'FINISHED'}
    after = helpers.aligned_share(obj, AXES)
    print("axis-aligned share: before %.3f after %.3f" % (before, after))
    assert before < MAX_SHARE_BEFORE
    assert after > MIN_CUBE_SHARE


def test_first_run_adds_a_cube_slot_and_uses_saved_step_count():
    obj = helpers.suzanne(levels=1)
    obj.gauss_stylization.iterations = 5
    start = helpers.coords(obj)
    assert bpy.ops.object.gauss_stylize() == {'FINISHED'}
    assert [s.preset for s in obj.gauss_stylization.styles] == ['CUBE']
    assert not np.array_equal(helpers.coords(obj), start)


def test_pinned_vertices_hold():
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    pinned = np.flatnonzero(start[:, 2] > 0.3)
    helpers.add_group(obj, "Pins", pinned)
    helpers.add_group(obj, "Light", np.flatnonzero(start[:, 2] < -0.3), weight=0.4)  # below 0.5
    assert helpers.stylize(30, pin_group="Pins") == {'FINISHED'}
    after = helpers.coords(obj)
    np.testing.assert_allclose(after[pinned], start[pinned], atol=1e-5)
    free = np.setdiff1d(np.arange(len(start)), pinned)
    assert np.abs(after[free] - start[free]).max() > 1e-2


def test_two_regions_take_their_own_styles():
    obj = helpers.uv_sphere(48, 24)
    start = helpers.coords(obj)
    helpers.add_group(obj, "Left", np.flatnonzero(start[:, 0] < 0))
    helpers.add_group(obj, "Right", np.flatnonzero(start[:, 0] >= 0))
    helpers.add_slot(obj, 'CUBE', "Left")
    helpers.add_slot(obj, 'OCTAHEDRON', "Right")
    assert helpers.stylize(100) == {'FINISHED'}
    tris, _ = helpers.triangles(obj)
    centers_x = start[tris].mean(axis=1)[:, 0]
    left, right = centers_x < -0.2, centers_x > 0.2  # away from the seam
    cube_left = helpers.aligned_share(obj, AXES, triangle_mask=left)
    octa_left = helpers.aligned_share(obj, OCTAHEDRON, triangle_mask=left)
    cube_right = helpers.aligned_share(obj, AXES, triangle_mask=right)
    octa_right = helpers.aligned_share(obj, OCTAHEDRON, triangle_mask=right)
    print("left cube %.3f octa %.3f | right cube %.3f octa %.3f"
          % (cube_left, octa_left, cube_right, octa_right))
    # measured: left cube 0.786 / octa 0.000, right cube 0.000 / octa 0.695
    assert cube_left > 0.5 and octa_left < 0.1
    assert octa_right > 0.45 and cube_right < 0.1


def test_uncovered_faces_can_stay_unstyled():
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > 0.2))
    helpers.add_slot(obj, 'CUBE', "Top")
    helpers.stylize(60, uncovered='UNSTYLED')
    unstyled = helpers.coords(obj)
    bpy.ops.object.gauss_stylize_reset()
    helpers.stylize(60, uncovered='FIRST_SLOT')
    first_slot = helpers.coords(obj)
    tris, _ = helpers.triangles(obj)
    bottom = start[tris].mean(axis=1)[:, 2] < -0.2
    share_unstyled = helpers.aligned_share(obj, AXES, unstyled, bottom)
    share_styled = helpers.aligned_share(obj, AXES, first_slot, bottom)
    print("bottom axis share: unstyled %.3f first slot %.3f" % (share_unstyled, share_styled))
    # measured: unstyled 0.133, first slot 0.784
    assert share_styled > share_unstyled + 0.4


def test_quads_and_ngons_keep_their_polygons():
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, end_fill_type='NGON')
    obj = bpy.context.active_object
    bpy.ops.mesh.primitive_monkey_add(location=(3, 0, 0))  # quads and triangles
    monkey = bpy.context.active_object
    sides = {}
    for o in (obj, monkey):
        sides[o.name] = [p.loop_total for p in o.data.polygons]
        helpers.activate(o)
        start = helpers.coords(o)
        assert helpers.stylize(20) == {'FINISHED'}
        assert [p.loop_total for p in o.data.polygons] == sides[o.name]
        assert not np.array_equal(helpers.coords(o), start)
    assert max(sides[obj.name]) == 12 and set(sides[monkey.name]) == {3, 4}


def test_solves_in_object_space_and_on_the_base_mesh():
    plain = helpers.suzanne(levels=1)
    helpers.stylize(20)
    moved = helpers.suzanne(levels=1)
    moved.location = (5, 1, 2)
    moved.rotation_euler = (0.4, 0.7, 1.1)
    moved.scale = (2, 2, 2)
    moved.modifiers.new("Subdivision", 'SUBSURF')
    polygons = len(moved.data.polygons)
    helpers.stylize(20)
    np.testing.assert_allclose(helpers.coords(moved), helpers.coords(plain), atol=1e-5)
    assert len(moved.data.polygons) == polygons and len(moved.modifiers) == 1


def test_every_selected_mesh_is_stylized():
    # Every selected mesh, not only the active object.
    other = helpers.suzanne(levels=0)
    other_start = helpers.coords(other)
    active = helpers.suzanne(levels=0)  # becomes the active object
    active_start = helpers.coords(active)
    other.select_set(True)
    assert helpers.stylize(10) == {'FINISHED'}
    assert not np.array_equal(helpers.coords(other), other_start)
    assert not np.array_equal(helpers.coords(active), active_start)
