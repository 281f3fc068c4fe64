"""Bad input: an error report in plain words, and the mesh left exactly as it was."""

import math

import bmesh
import bpy
import numpy as np
import pytest

import helpers


def _snapshot(obj):
    keys = obj.data.shape_keys
    names = [k.name for k in keys.key_blocks] if keys else []
    return helpers.coords(obj), names


def _assert_refused(obj, message):
    before = _snapshot(obj)
    with pytest.raises(RuntimeError, match=message):
        bpy.ops.object.gauss_stylize(iterations=5)
    after = _snapshot(obj)
    assert np.array_equal(before[0], after[0], equal_nan=True) and before[1] == after[1]


def _suzanne_with_slot(**values):
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, **values)
    return obj


def test_empty_mesh():
    obj = helpers.object_from_bmesh(bmesh.new(), "Empty")
    _assert_refused(obj, "no vertices")


def test_mesh_without_faces():
    bm = bmesh.new()
    a, b = bm.verts.new((0, 0, 0)), bm.verts.new((1, 0, 0))
    bm.edges.new((a, b))
    _assert_refused(helpers.object_from_bmesh(bm, "Edge"), "no faces")


def test_broken_coordinates():
    obj = helpers.suzanne(levels=0)
    obj.data.vertices[3].co = (math.nan, 0, 0)
    _assert_refused(obj, "NaN")


def test_nan_sigma():
    obj = _suzanne_with_slot(preset='CUBE')
    obj.gauss_stylization.styles[0].sigma = math.nan
    _assert_refused(obj, "Sigma")


def test_nan_lambda():
    obj = _suzanne_with_slot(preset='CUBE')
    obj.gauss_stylization.lam = math.nan
    _assert_refused(obj, "Lambda")


def test_huge_mu_is_clamped_to_a_sane_range():
    obj = _suzanne_with_slot(preset='CUBE')
    obj.gauss_stylization.styles[0].mu = 1e30
    assert obj.gauss_stylization.styles[0].mu == 1000.0


def test_missing_style_vertex_group():
    obj = _suzanne_with_slot(preset='CUBE', group="Ears")
    _assert_refused(obj, "no vertex group 'Ears'")


def test_missing_pin_group():
    obj = _suzanne_with_slot(preset='CUBE')
    obj.gauss_stylization.pin_group = "Nails"
    _assert_refused(obj, "Pin Group: there is no vertex group 'Nails'")


def test_custom_style_without_normals():
    obj = _suzanne_with_slot(preset='CUSTOM')
    _assert_refused(obj, "no normals")


def test_zero_custom_normal_added_in_the_ui():
    obj = _suzanne_with_slot(preset='CUSTOM')
    obj.gauss_stylization.styles[0].custom_normals.add().vector = (0, 0, 0)
    _assert_refused(obj, "zero length")


def test_absolute_shape_keys_with_shape_key_output():
    obj = _suzanne_with_slot(preset='CUBE')
    obj.shape_key_add(name="Basis")
    obj.shape_key_add(name="Other")
    obj.data.shape_keys.use_relative = False
    obj.gauss_stylization.output = 'SHAPE_KEY'
    _assert_refused(obj, "absolute shape keys")


def test_non_mesh_object():
    camera = bpy.data.objects.new("Cam", bpy.data.cameras.new("Cam"))
    bpy.context.scene.collection.objects.link(camera)
    helpers.activate(camera)
    with pytest.raises(RuntimeError, match="'Cam' is not a mesh"):
        bpy.ops.object.gauss_stylize(iterations=5)


def test_edit_mode():
    helpers.suzanne(levels=0)
    bpy.ops.object.mode_set(mode='EDIT')
    try:
        with pytest.raises(RuntimeError, match="Object Mode"):
            bpy.ops.object.gauss_stylize(iterations=5)
    finally:
        bpy.ops.object.mode_set(mode='OBJECT')


def test_solver_rejection_becomes_a_report(monkeypatch, addon):
    obj = _suzanne_with_slot(preset='CUBE')
    gauss_core = addon.native.core()

    class Refusing:
        def __init__(self, *args, **kwargs):
            raise ValueError("mesh is not manifold")

    monkeypatch.setattr(gauss_core, "Solver", Refusing)
    _assert_refused(obj, "mesh is not manifold")


@pytest.mark.parametrize("name", ["degtri_sliding_zero_area.obj", "fan3_nonmanifold_edge.obj"])
def test_broken_meshes_from_the_corpus(name):
    obj = helpers.import_obj("bad/" + name)
    before = helpers.coords(obj)
    try:
        result = bpy.ops.object.gauss_stylize(iterations=20)
    except RuntimeError:
        assert np.array_equal(helpers.coords(obj), before)  # refused: untouched
    else:
        assert result == {'FINISHED'} and np.isfinite(helpers.coords(obj)).all()


def test_solver_producing_nan_is_reported_and_undone(monkeypatch, addon):
    obj = _suzanne_with_slot(preset='CUBE')
    gauss_core = addon.native.core()
    real = gauss_core.Solver

    class Diverging:
        def __init__(self, *args, **kwargs):
            self.inner = real(*args, **kwargs)

        def __getattr__(self, name):
            return getattr(self.inner, name)

        def vertices_into(self, out):
            out[...] = math.nan

    monkeypatch.setattr(gauss_core, "Solver", Diverging)
    _assert_refused(obj, "invalid positions")
    assert len(obj.gauss_stylization.styles) == 1
