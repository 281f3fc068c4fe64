"""Style Reach (sphere/style_reach.py, sphere/reach_overlay.py, reach_operators.py): each face's angle
to the normal its style prefers, as the overlay draws it, as the face attribute 'gauss_style_angle',
and as a selection."""
import math

import bmesh
import bpy
import numpy as np
import pytest

import helpers


def _cube(subdivisions=2):
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=2.0)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=subdivisions, use_grid_fill=True)
    obj = helpers.object_from_bmesh(bm, "Cube")
    bm.free()
    helpers.activate(obj)
    return obj


def _angles(addon, obj):
    return addon.reach_operators.polygon_angles(obj)


def test_a_cube_reaches_the_cube_style_and_a_turned_cube_style_is_45_degrees_off(addon):
    obj = _cube()
    slot = helpers.add_slot(obj, 'CUBE')
    assert np.allclose(_angles(addon, obj), 0.0, atol=1e-3)
    slot.orientation = (0.0, 0.0, math.radians(45.0))
    normals = np.empty((len(obj.data.polygons), 3), np.float32)
    obj.data.polygons.foreach_get("normal", normals.reshape(-1))
    sides = np.abs(normals[:, 2]) < 0.5
    angles = _angles(addon, obj)
    assert np.allclose(angles[sides], 45.0, atol=1e-3) and np.allclose(angles[~sides], 0.0, atol=1e-3)


def test_the_cubic_method_measures_against_each_slots_turned_cube(addon):
    obj = _cube()
    slot = helpers.add_slot(obj, 'TETRAHEDRON')  # the Cubic method does not use the Style
    obj.gauss_stylization.method = 'CUBIC'
    assert np.allclose(_angles(addon, obj), 0.0, atol=1e-3)
    slot.orientation = (math.radians(30.0), 0.0, 0.0)
    assert _angles(addon, obj).max() == pytest.approx(30.0, abs=1e-3)


def test_faces_no_slot_stylizes_have_no_angle_and_store_minus_one(addon):
    obj = _cube()
    co = helpers.coords(obj)
    helpers.add_group(obj, "Top", np.flatnonzero(co[:, 2] > 0.99))
    helpers.add_slot(obj, 'CUBE', group="Top")
    angles = _angles(addon, obj)
    centres = np.empty((len(obj.data.polygons), 3), np.float32)
    obj.data.polygons.foreach_get("center", centres.reshape(-1))
    top = centres[:, 2] > 0.99
    assert np.isfinite(angles[top]).all() and np.isnan(angles[~top]).all()
    assert bpy.ops.object.gauss_store_style_angles() == {'FINISHED'}
    stored = np.empty(len(obj.data.polygons), np.float32)
    attribute = obj.data.attributes[addon.reach_operators.ATTRIBUTE]
    assert (attribute.domain, attribute.data_type) == ('FACE', 'FLOAT')
    attribute.data.foreach_get("value", stored)
    assert np.allclose(stored[top], 0.0, atol=1e-3) and (stored[~top] == -1.0).all()


def test_sheet_metal_is_reached_on_a_rolled_sheet_and_not_on_a_sphere(addon):
    bpy.ops.mesh.primitive_cylinder_add(vertices=48, depth=2.0, end_fill_type='NOTHING')
    tube = bpy.context.active_object
    helpers.add_slot(tube, 'SHEET_METAL')
    assert np.nanmax(_angles(addon, tube)) < 1e-2
    sphere = helpers.uv_sphere(32, 16)
    helpers.activate(sphere)
    helpers.add_slot(sphere, 'SHEET_METAL')
    assert np.nanmin(_angles(addon, sphere)) > 1.0


def test_stylizing_brings_the_angles_down_and_the_attribute_is_rewritten(addon):
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'CUBE')
    assert bpy.ops.object.gauss_store_style_angles() == {'FINISHED'}
    first = np.empty(len(obj.data.polygons), np.float32)
    obj.data.attributes["gauss_style_angle"].data.foreach_get("value", first)
    assert helpers.stylize(100) == {'FINISHED'}
    assert bpy.ops.object.gauss_store_style_angles() == {'FINISHED'}
    second = np.empty_like(first)
    obj.data.attributes["gauss_style_angle"].data.foreach_get("value", second)
    assert len([a for a in obj.data.attributes if a.name == "gauss_style_angle"]) == 1
    assert second.mean() < 0.6 * first.mean(), (first.mean(), second.mean())


def test_select_unreached_selects_exactly_the_faces_at_or_past_the_angle(addon):
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'CUBE')
    angles = _angles(addon, obj)
    assert bpy.ops.object.gauss_select_unreached(angle=20.0) == {'FINISHED'}
    if obj.mode == 'EDIT':
        bpy.ops.object.mode_set(mode='OBJECT')
    selected = np.zeros(len(obj.data.polygons), bool)
    obj.data.polygons.foreach_get("select", selected)
    assert selected.any() and np.array_equal(selected, angles >= 20.0)


def test_the_overlay_follows_a_live_run_and_the_operators_wait_for_it(addon):
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'CUBE')
    obj.gauss_stylization.show_style_reach = True
    overlay = addon.sphere.reach_overlay
    before = overlay._entry(obj)["angles"].copy()
    live = helpers.live_run([obj])
    runs = addon.run.runs
    runs.start([obj], live)
    try:
        for _ in range(40):
            live.tick(budget=1e9)
        assert np.array_equal(overlay.surface_of(obj)[0], live.sessions[0].result)
        during = overlay._entry(obj, force=True)["angles"]  # force: however soon after the last refresh
        assert np.nanmean(during) < 0.7 * np.nanmean(before)
        assert not bpy.ops.object.gauss_store_style_angles.poll()
        assert not bpy.ops.object.gauss_select_unreached.poll()
    finally:
        runs.forget(live)
        live.cancel()


def test_a_slot_that_cannot_be_built_is_named_instead_of_drawn(addon):
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, 'CUSTOM')
    obj.gauss_stylization.show_style_reach = True
    entry = addon.sphere.reach_overlay._entry(obj)
    assert entry["positions"] is None and "Custom" in entry["problem"], entry.get("problem")
    with pytest.raises(RuntimeError, match="Style 'Custom' is set to Custom but has no normals"):
        bpy.ops.object.gauss_store_style_angles()


def test_the_colour_scale(addon):
    colours = addon.sphere.style_reach.colours(np.array([0.0, 15.0, 30.0, 90.0, np.nan]))
    green, yellow, red, past, grey = colours[:, :3]
    assert green[1] > 0.6 > green[0] and red[0] > 0.8 > red[1] and np.array_equal(red, past)
    assert yellow[0] > 0.8 and yellow[1] > 0.8
    assert np.allclose(grey, addon.sphere.style_reach.UNSTYLED)


def test_the_overlay_keeps_its_angles_until_something_they_depend_on_changes(addon):
    obj = _cube()
    slot = helpers.add_slot(obj, 'CUBE')
    obj.gauss_stylization.show_style_reach = True
    overlay = addon.sphere.reach_overlay
    first = overlay._entry(obj)
    angles, computed = first["angles"], first["time"]
    assert overlay._entry(obj, force=True)["angles"] is angles  # nothing changed: nothing computed
    slot.orientation = (0.0, 0.0, math.radians(45.0))  # a style field
    turned = overlay._entry(obj, force=True)["angles"]
    assert turned is not angles and np.nanmax(turned) == pytest.approx(45.0, abs=1e-3)
    co = helpers.coords(obj)
    co[:, 2] *= 1.5  # the mesh changed by another tool: the sides keep their normals, so move one vertex
    co[0] += [0.3, 0.0, 0.0]
    helpers.mesh_io.write_vertex_coords(obj.data, co)
    obj.data.update()
    moved = overlay._entry(obj, force=True)["angles"]
    assert moved is not turned
    helpers.add_group(obj, "Top", np.flatnonzero(co[:, 2] > 1.49))
    slot.vertex_group = "Top"  # a Region
    regional = overlay._entry(obj, force=True)["angles"]
    assert np.isnan(regional).sum() > 0 and np.isfinite(regional).sum() > 0
    # A shape that keeps changing (a drag, sculpting) is measured again only after a while (a timer redraws
    # then), not at every redraw; a setting's change is shown at once.
    co[1] += [0.0, 0.2, 0.0]
    helpers.mesh_io.write_vertex_coords(obj.data, co)
    assert overlay._entry(obj)["angles"] is regional
    slot.orientation = (0.0, 0.0, 0.0)
    assert overlay._entry(obj)["angles"] is not regional


def test_a_deleted_region_group_is_named_not_raised(addon):
    obj = _cube()
    helpers.add_group(obj, "Gone", [0, 1, 2])
    helpers.add_slot(obj, 'CUBE', group="Gone")
    obj.vertex_groups.remove(obj.vertex_groups["Gone"])
    obj.gauss_stylization.show_style_reach = True
    entry = addon.sphere.reach_overlay._entry(obj)
    assert entry["positions"] is None and "'Gone', no longer exists" in entry["problem"]
    with pytest.raises(RuntimeError, match="no longer exists"):
        bpy.ops.object.gauss_select_unreached()


def test_coordinates_that_are_not_finite_are_named(addon):
    obj = _cube()
    helpers.add_slot(obj, 'CUBE')
    co = helpers.coords(obj)
    co[3] = np.nan
    helpers.mesh_io.write_vertex_coords(obj.data, co)
    obj.gauss_stylization.show_style_reach = True
    entry = addon.sphere.reach_overlay._entry(obj)
    assert entry["positions"] is None and "not finite" in entry["problem"]
    assert addon.sphere.reach_overlay._entry(obj)["key"] == entry["key"]  # NaN keys still match: no recompute


def test_shape_keys_are_measured_as_shown(addon):
    obj = _cube()
    helpers.add_slot(obj, 'TETRAHEDRON')
    obj.shape_key_add(name="Basis")
    flat = obj.shape_key_add(name="Flat")
    co = helpers.coords(obj)
    co[:, 2] = np.where(co[:, 2] > 0, 1.0, -1.0)
    helpers.key_coords and flat.data.foreach_set("co", co.reshape(-1))
    flat.value = 1.0
    obj.data.update()
    shown = addon.sphere.reach_overlay.surface_of(obj)[0]
    assert np.allclose(shown, co)


def test_the_look_lambda_covers_every_preset_with_a_lambda_of_its_own(addon):
    assert set(addon.settings.schema.LOOK_LAMBDA) == set(addon.native.core().PRESET_LAMBDA)


def test_the_axis_normals_of_a_ring_preset_count_only_with_an_axis_weight(addon):
    obj = _cube(0)
    slot = helpers.add_slot(obj, 'CYLINDER')
    normals = np.empty((len(obj.data.polygons), 3), np.float32)
    obj.data.polygons.foreach_get("normal", normals.reshape(-1))
    caps = np.abs(normals[:, 2]) > 0.5
    assert np.allclose(_angles(addon, obj)[caps], 0.0, atol=1e-3)
    slot.axis_contribution = 0.0
    assert np.allclose(_angles(addon, obj)[caps], 90.0, atol=1e-3)
