"""Settings of files saved by an earlier version keep their result (settings/versioning.py): Other
Faces now defaults to Unstyled, so a Region on the only slot paints it, while a file saved when the
default was First Style (which made that Region whole again) still stylizes as it did."""

import bpy
import numpy as np

import helpers


def _result(addon, obj, steps=8):
    run = addon.run.session.Session(obj)
    run.step(steps)
    out = helpers.coords(obj)
    run.cancel()
    return out


def _half_painted_sphere(name="Sphere"):
    """A UV sphere with one Cube slot whose Region weighs 0.5 everywhere; Other Faces never set."""
    obj = helpers.uv_sphere()
    obj.name = name
    helpers.add_group(obj, "Paint", range(len(obj.data.vertices)), weight=0.5)
    helpers.add_slot(obj, 'CUBE', "Paint")
    assert not obj.gauss_stylization.is_property_set("uncovered")
    return obj


def _unpainted_result(addon, obj):
    slot = obj.gauss_stylization.styles[0]
    slot.vertex_group = ""
    try:
        return _result(addon, obj)
    finally:
        slot.vertex_group = "Paint"


def _save_as_an_earlier_version_did(addon, path):
    """Write the file without the stamp (settings_version), as versions before it wrote every file."""
    versioning = addon.settings.versioning
    for obj in bpy.data.objects:
        obj.gauss_stylization.property_unset(versioning.STAMP)
    versioning.unregister_handlers()
    try:
        bpy.ops.wm.save_as_mainfile(filepath=path)
    finally:
        versioning.register_handlers()


def test_a_region_on_the_only_slot_paints_it(addon):
    obj = _half_painted_sphere()
    assert obj.gauss_stylization.uncovered == 'UNSTYLED'
    assert not np.array_equal(_result(addon, obj), _unpainted_result(addon, obj))


def _as_version_0_ran(obj):
    """The settings a version-0 object ran with where it never set them (the old defaults)."""
    obj.gauss_stylization.resolution_independent = False


def test_a_file_saved_with_the_old_default_keeps_its_result(addon, tmp_path):
    obj = _half_painted_sphere()
    _as_version_0_ran(obj)
    obj.gauss_stylization.uncovered = 'FIRST_SLOT'  # what the old default gave it
    old_result = _result(addon, obj)
    assert np.array_equal(old_result, _unpainted_result(addon, obj))  # the old rule: the paint did nothing
    obj.gauss_stylization.property_unset("uncovered")  # as the old version saved it: never set
    explicit = _half_painted_sphere("Chosen")
    _as_version_0_ran(explicit)
    explicit.gauss_stylization.uncovered = 'UNSTYLED'  # set by hand in the old version: kept
    chosen_result = _result(addon, explicit)
    for each in (obj, explicit):
        each.gauss_stylization.property_unset("resolution_independent")  # a setting version 0 did not know
    path = str(tmp_path / "old.blend")
    _save_as_an_earlier_version_did(addon, path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)

    obj, explicit = bpy.data.objects["Sphere"], bpy.data.objects["Chosen"]
    settings = obj.gauss_stylization
    assert settings.uncovered == 'FIRST_SLOT' and settings.is_property_set("uncovered")
    assert settings.settings_version == addon.settings.versioning.VERSION
    assert np.array_equal(_result(addon, obj), old_result)
    assert explicit.gauss_stylization.uncovered == 'UNSTYLED'
    assert np.array_equal(_result(addon, explicit), chosen_result)


def test_a_file_saved_now_keeps_the_new_default(addon, tmp_path):
    obj = _half_painted_sphere()
    painted = _result(addon, obj)
    path = str(tmp_path / "new.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)

    obj = bpy.data.objects["Sphere"]
    assert obj.gauss_stylization.uncovered == 'UNSTYLED'
    assert not obj.gauss_stylization.is_property_set("uncovered")  # still the default, not written out
    assert np.array_equal(_result(addon, obj), painted)


def test_first_style_keeps_the_last_free_slot_and_unstyled_takes_the_first(addon):
    # Two slots without a Region and one with: First Style keeps the rule it always had (the last
    # free slot fills), the default gives what the Regions leave to the first free slot.
    obj = helpers.uv_sphere()
    helpers.add_group(obj, "Paint", range(len(obj.data.vertices)), weight=0.25)
    for preset, group in (('CUBE', ""), ('OCTAHEDRON', ""), ('TETRAHEDRON', "Paint")):
        helpers.add_slot(obj, preset, group)
    plan = addon.run.session.Plan(obj)
    try:
        weights = plan.regions[0]
        obj.gauss_stylization.uncovered = 'FIRST_SLOT'
        old = addon.settings.styles.face_weights(plan.arrays, plan.weights, ["", "", "Paint"], 'FIRST_SLOT',
                                                 plan.paint_steepness)
    finally:
        plan.release()
    np.testing.assert_array_equal(weights[:, 0], 0.75)
    np.testing.assert_array_equal(weights[:, 1:], np.broadcast_to([0.0, 0.25], (len(weights), 2)))
    np.testing.assert_array_equal(old[:, 0], 0.0)
    np.testing.assert_array_equal(old[:, 1:], np.broadcast_to([0.75, 0.25], (len(old), 2)))
