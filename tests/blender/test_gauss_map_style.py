"""The Gauss Map style end to end: From Gauss Map (bpy.ops.object.gauss_style_from_gauss_map) stores an
example's whole normal distribution in a new slot, which scripted runs, live runs and bakes stylize
towards, and which survives saving and reopening the .blend."""

import bmesh
import bpy
import numpy as np
import pytest
from mathutils import Euler

import helpers
from measures import fibonacci_lattice, gauss_histogram, mesh_gauss_histogram, sphere_emd


def _cube(name="Example"):
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=2.0)
    return helpers.object_from_bmesh(bm, name)


def _from_gauss_map(target, source):
    helpers.activate(target)
    return bpy.ops.object.gauss_style_from_gauss_map(source=source.name)


def _rows(obj):
    settings = obj.gauss_stylization
    slot = settings.styles[settings.active_style_index]
    assert slot.preset == 'GAUSS_MAP'
    return slot.gauss_map_array()


def test_a_cube_gives_its_six_axes_each_with_a_sixth_of_the_area():
    example = _cube()
    target = helpers.suzanne(levels=0)
    helpers.add_slot(target, 'CUBE')
    assert _from_gauss_map(target, example) == {'FINISHED'}
    settings = target.gauss_stylization
    assert len(settings.styles) == 2 and settings.active_style_index == 1  # added, made active
    assert settings.styles[1].name == "Gauss Map of Example"
    rows = _rows(target)
    assert len(rows) == 6
    assert np.allclose(np.sort(rows[:, :3] @ helpers.AXES.T, axis=1)[:, -1], 1.0, atol=1e-6)
    assert np.allclose(rows[:, 3], 1 / 6, atol=1e-6)


def test_directions_are_turned_by_the_two_objects_rotations():
    example = _cube()
    example.rotation_euler = np.radians((0.0, 0.0, 30.0))
    target = helpers.suzanne(levels=0)
    target.rotation_euler = np.radians((0.0, 0.0, 10.0))
    bpy.context.view_layer.update()
    assert _from_gauss_map(target, example) == {'FINISHED'}
    # The example's axes as the target sees them: turned by 30 - 10 = 20 degrees about Z.
    turned = helpers.AXES @ np.array(Euler((0.0, 0.0, np.radians(20.0))).to_matrix()).T
    assert np.allclose(np.sort(_rows(target)[:, :3] @ turned.T, axis=1)[:, -1], 1.0, atol=1e-5)


def test_it_refuses_what_has_no_faces_and_adds_nothing():
    target = helpers.suzanne(levels=0)
    with pytest.raises(RuntimeError, match="there is no object 'Nothing'"):
        bpy.ops.object.gauss_style_from_gauss_map(source="Nothing")
    empty = bpy.data.objects.new("Empty", None)
    bpy.context.scene.collection.objects.link(empty)
    helpers.activate(target)
    with pytest.raises(RuntimeError, match="'Empty' is not a mesh"):
        bpy.ops.object.gauss_style_from_gauss_map(source="Empty")
    wire = bpy.data.meshes.new("Wire")
    wire.from_pydata([(0, 0, 0), (1, 0, 0)], [(0, 1)], [])
    wire_obj = bpy.data.objects.new("Wire", wire)
    bpy.context.scene.collection.objects.link(wire_obj)
    with pytest.raises(RuntimeError, match="no faces with area"):
        _from_gauss_map(target, wire_obj)
    assert len(target.gauss_stylization.styles) == 0


def test_a_slot_without_an_example_is_refused_with_a_message():
    target = helpers.suzanne(levels=0)
    helpers.add_slot(target, 'GAUSS_MAP')
    start = helpers.coords(target)
    with pytest.raises(RuntimeError, match="has no example"):
        helpers.stylize(5)
    assert np.array_equal(helpers.coords(target), start)


def test_a_cubes_gauss_map_stylizes_as_the_cube_style():
    # The bar: within 0.03 of the Cube style's share of faces within 10 degrees of the axes.
    example = _cube()
    cube = helpers.suzanne(levels=1)
    helpers.add_slot(cube, 'CUBE')
    assert helpers.stylize(60) == {'FINISHED'}
    target = helpers.suzanne(levels=1)
    assert _from_gauss_map(target, example) == {'FINISHED'}
    assert helpers.stylize(60) == {'FINISHED'}
    share, cube_share = helpers.aligned_share(target, helpers.AXES), helpers.aligned_share(cube, helpers.AXES)
    assert share > 0.5 and abs(share - cube_share) <= 0.03, (share, cube_share)


def test_the_result_comes_closer_to_the_example_than_the_input_and_no_further_than_from_object():
    # An icosahedron's 20 directions. Measured (Suzanne, 60 steps): EMD 0.326 before, 0.294 after, as
    # From Object's result (its 20 directions are all of the example's).
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1)
    example = bpy.context.active_object
    lattice = fibonacci_lattice(200)
    wanted = gauss_histogram(np.array([p.normal for p in example.data.polygons]),
                             np.array([p.area for p in example.data.polygons]), lattice)
    emd = {}
    for name, operator in (("gauss_map", _from_gauss_map), ("from_object", None)):
        target = helpers.suzanne(levels=1)
        emd["input"] = sphere_emd(mesh_gauss_histogram(helpers.coords(target), helpers.triangles(target)[0],
                                                       lattice), wanted, lattice)
        if operator:
            assert operator(target, example) == {'FINISHED'}
        else:
            helpers.activate(target)
            assert bpy.ops.object.gauss_style_from_object(source=example.name) == {'FINISHED'}
        assert helpers.stylize(60) == {'FINISHED'}
        assert np.isfinite(helpers.coords(target)).all()
        emd[name] = sphere_emd(mesh_gauss_histogram(helpers.coords(target), helpers.triangles(target)[0],
                                                    lattice), wanted, lattice)
    assert emd["gauss_map"] < 0.95 * emd["input"], emd
    assert emd["gauss_map"] <= emd["from_object"] + 0.001, emd


def test_the_style_survives_save_and_reopen_and_stylizes_the_same(tmp_path):
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1)
    example = bpy.context.active_object
    target = helpers.suzanne(levels=1)
    start = helpers.coords(target)
    assert _from_gauss_map(target, example) == {'FINISHED'}
    rows = _rows(target)
    assert helpers.stylize(20) == {'FINISHED'}
    stylized = helpers.coords(target)
    helpers.mesh_io.write_vertex_coords(target.data, start)  # the next run starts where this one did
    target.data.update()
    path = str(tmp_path / "gauss_map.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    target = bpy.data.objects["Suzanne"]
    helpers.activate(target)
    assert np.array_equal(_rows(target), rows)
    assert helpers.stylize(20) == {'FINISHED'}
    assert np.array_equal(helpers.coords(target), stylized)


def test_a_live_run_and_a_bake_use_the_style(addon, tmp_path):
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1)
    example = bpy.context.active_object
    target = helpers.suzanne(levels=1)
    start = helpers.coords(target)
    assert _from_gauss_map(target, example) == {'FINISHED'}
    # A live run's steps are a scripted run's steps.
    live = helpers.live_run([target])
    for _ in range(5):
        live.tick(budget=1e9)
    session = live.sessions[0]
    steps = session.steps
    assert steps > 0
    shown = helpers.coords(target)
    live.cancel()
    assert np.array_equal(helpers.coords(target), start)  # cancelling restores exactly
    helpers.activate(target)
    assert helpers.stylize(steps) == {'FINISHED'}
    assert np.allclose(helpers.coords(target), shown, atol=1e-5)
    # A bake of the run, step by step, ends where a scripted run of as many steps does.
    helpers.mesh_io.write_vertex_coords(target.data, start)
    target.data.update()
    path = tmp_path / "progress.pc2"
    assert bpy.ops.object.gauss_bake_progress(steps=6, steps_per_frame=3, filepath=str(path)) == {'FINISHED'}
    cache = addon.pc2.read(str(path))
    assert helpers.stylize(6) == {'FINISHED'}
    assert np.array_equal(cache.frames[-1], helpers.coords(target))
