"""Bad input: an error report in plain words, and the mesh left exactly as it was."""

import json
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


def _solver_writing(monkeypatch, addon, change):
    """gauss_core.Solver replaced by one whose vertices_into() passes its result through ``change``."""
    gauss_core = addon.native.core()
    real = gauss_core.Solver

    class Changed:
        def __init__(self, *args, **kwargs):
            self.inner = real(*args, **kwargs)

        def __getattr__(self, name):
            return getattr(self.inner, name)

        def vertices_into(self, out):
            self.inner.vertices_into(out)
            change(out)

    monkeypatch.setattr(gauss_core, "Solver", Changed)


def test_solver_producing_nan_is_reported_and_undone(monkeypatch, addon):
    obj = _suzanne_with_slot(preset='CUBE')
    _solver_writing(monkeypatch, addon, lambda out: out.fill(math.nan))
    _assert_refused(obj, "invalid positions")
    assert len(obj.gauss_stylization.styles) == 1


def test_no_active_object():
    obj = helpers.suzanne(levels=0)
    before = helpers.coords(obj)
    bpy.context.view_layer.objects.active = None
    assert not bpy.ops.object.gauss_stylize.poll()
    for operator in (bpy.ops.object.gauss_stylize, bpy.ops.object.gauss_stylize_reset):
        with pytest.raises(RuntimeError, match="Select a mesh object first"):
            operator()
    assert np.array_equal(helpers.coords(obj), before) and len(obj.gauss_stylization.styles) == 0


def test_vertex_group_deleted_while_its_name_is_stored():
    obj = _suzanne_with_slot(preset='CUBE', group="Ears")
    helpers.add_group(obj, "Ears", range(50))
    helpers.add_group(obj, "Nails", range(5))
    obj.gauss_stylization.pin_group = "Nails"
    obj.vertex_groups.remove(obj.vertex_groups["Ears"])
    _assert_refused(obj, "Style 'Cube': there is no vertex group 'Ears'")
    obj.gauss_stylization.styles[0].vertex_group = ""
    obj.vertex_groups.remove(obj.vertex_groups["Nails"])
    _assert_refused(obj, "Pin Group: there is no vertex group 'Nails'")


# Non-finite and huge values set from Python. Blender clamps +-inf and huge
# values of the ranged properties into their documented range (and vectors to
# +-FLT_MAX) but lets NaN through. Expected: the error naming the setting, or,
# for what was clamped to a usable value, a normal run with a finite result.
FLOAT_CASES = [
    ("settings", "lam", math.nan, "Lambda"),
    ("settings", "lam", math.inf, None),
    ("settings", "lam", -math.inf, None),
    ("slot", "sigma", math.nan, "Sigma"),
    ("slot", "sigma", 1e30, None),
    ("slot", "sigma", -1e30, None),  # clamped to the lower limit (LIMITS), which runs
    ("slot", "mu", math.nan, "Mu"),
    ("slot", "mu", math.inf, None),
    ("slot", "mu", -math.inf, None),
    ("slot", "axis_contribution", math.nan, "Axis Contribution"),
    ("slot", "axis_contribution", math.inf, None),
    ("slot", "axis_contribution", -1e30, None),
    ("slot", "orientation", math.nan, "Orientation"),
    ("slot", "orientation", math.inf, None),  # stored as FLT_MAX: still some rotation
    ("normal", "vector", math.nan, "custom normal 1 is not a finite vector"),
    ("normal", "vector", math.inf, None),
    ("normal", "vector", -1e30, None),
    ("normal", "vector", 1e-30, "custom normal 1 has zero length"),
]


@pytest.mark.parametrize("owner, name, value, error", FLOAT_CASES,
                         ids=["%s-%s-%g" % case[:3] for case in FLOAT_CASES])
def test_extreme_float_setting_from_python(owner, name, value, error):
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, 'CUSTOM' if owner == "normal" else 'CUBE')
    if owner == "normal":
        slot.set_custom_normals([(0, 0, 1)])
    target = {"settings": obj.gauss_stylization, "slot": slot,
              "normal": slot.custom_normals[0] if owner == "normal" else None}[owner]
    size = target.bl_rna.properties[name].array_length
    setattr(target, name, (value,) * size if size else value)
    stored = list(getattr(target, name)) if size else [getattr(target, name)]
    if error is not None:
        _assert_refused(obj, error)
        return
    prop = target.bl_rna.properties[name]
    assert all(prop.hard_min <= v <= prop.hard_max for v in stored)  # clamped, so not NaN either
    assert bpy.ops.object.gauss_stylize(iterations=5) == {'FINISHED'}
    assert np.isfinite(helpers.coords(obj)).all()


@pytest.mark.parametrize("name, low, high", [("iterations", 0, 100000), ("admm_iterations", 1, 100)])
def test_extreme_int_setting_from_python(name, low, high):
    settings = helpers.suzanne(levels=0).gauss_stylization
    before = getattr(settings, name)
    for bad, error in ((math.nan, TypeError), (math.inf, TypeError), (10 ** 10, ValueError),
                       (-2 ** 31 - 1, ValueError)):
        with pytest.raises(error):
            setattr(settings, name, bad)
        assert getattr(settings, name) == before
    setattr(settings, name, -10 ** 9)
    assert getattr(settings, name) == low
    setattr(settings, name, 10 ** 9)
    assert getattr(settings, name) == high


def test_most_admm_iterations_run():
    obj = _suzanne_with_slot(preset='CUBE')
    obj.gauss_stylization.admm_iterations = 10 ** 9  # clamped to 100
    assert helpers.stylize(3) == {'FINISHED'} and np.isfinite(helpers.coords(obj)).all()


def test_extreme_operator_iterations_from_python():
    obj = _suzanne_with_slot(preset='CUBE')
    before = helpers.coords(obj)
    for bad, error in ((math.nan, TypeError), (10 ** 10, ValueError)):
        with pytest.raises(error):
            bpy.ops.object.gauss_stylize(iterations=bad)
        assert np.array_equal(helpers.coords(obj), before)
    # Clamped to 0, which runs until converged (at most schema.UNTIL_CONVERGED_CAP steps).
    assert bpy.ops.object.gauss_stylize(iterations=-5) == {'FINISHED'}
    after = helpers.coords(obj)
    assert np.isfinite(after).all() and not np.array_equal(after, before)


def test_nan_in_settings_json(addon):
    obj = _suzanne_with_slot(preset='CUBE')
    before = helpers.coords(obj)
    settings = json.loads(addon.settings_io.to_json(obj.gauss_stylization))
    settings["styles"][0]["mu"] = math.nan
    with pytest.raises(RuntimeError, match="Mu must be a number"):
        bpy.ops.object.gauss_stylize(iterations=5, settings_json=json.dumps(settings))
    assert np.array_equal(helpers.coords(obj), before)


def test_all_vertices_pinned_says_nothing_can_move():
    # A run that can move nothing must say so instead of finishing silently.
    obj = _suzanne_with_slot(preset='CUBE')
    helpers.add_group(obj, "Everything", range(len(obj.data.vertices)))
    obj.gauss_stylization.pin_group = "Everything"
    _assert_refused(obj, "Every vertex of 'Suzanne' is in the Pin Group 'Everything', so nothing can move")


@pytest.mark.parametrize("value, said", [(1e6, "more than 100 times the mesh's size away"), (math.inf, "not finite")])
def test_a_blown_up_result_is_refused_with_an_accurate_message(monkeypatch, addon, value, said):
    # A blow-up is the solver's defect, so the message must not send the artist to Lambda or the mesh;
    # a finite one (the hole-filled bunny can reach 1e20 times its size) is refused too, never written.
    obj = _suzanne_with_slot(preset='CUBE')
    _solver_writing(monkeypatch, addon, lambda out: out.__setitem__(7, value))
    _assert_refused(obj, "invalid positions after step 1 \\(%s\\).*a defect of the solver, not of your settings" % said)
