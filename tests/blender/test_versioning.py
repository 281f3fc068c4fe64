"""Settings of files saved by an earlier version keep their result (settings/versioning.py): Other
Faces now defaults to Unstyled, so a Region on the only slot paints it, while a file saved when the
default was First Style (which made that Region whole again) still stylizes as it did."""

import json

import bpy
import numpy as np
import pytest

import helpers


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
        return helpers.stepped_result(addon, obj)
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
    assert not np.array_equal(helpers.stepped_result(addon, obj), _unpainted_result(addon, obj))


def _as_version_0_ran(obj):
    """The settings a version-0 object ran with where it never set them (the old defaults)."""
    obj.gauss_stylization.resolution_independent = False


def test_a_file_saved_with_the_old_default_keeps_its_result(addon, tmp_path):
    obj = _half_painted_sphere()
    _as_version_0_ran(obj)
    obj.gauss_stylization.uncovered = 'FIRST_SLOT'  # what the old default gave it
    old_result = helpers.stepped_result(addon, obj)
    assert np.array_equal(old_result, _unpainted_result(addon, obj))  # the old rule: the paint did nothing
    obj.gauss_stylization.property_unset("uncovered")  # as the old version saved it: never set
    explicit = _half_painted_sphere("Chosen")
    _as_version_0_ran(explicit)
    explicit.gauss_stylization.uncovered = 'UNSTYLED'  # set by hand in the old version: kept
    chosen_result = helpers.stepped_result(addon, explicit)
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
    assert np.array_equal(helpers.stepped_result(addon, obj), old_result)
    assert explicit.gauss_stylization.uncovered == 'UNSTYLED'
    assert np.array_equal(helpers.stepped_result(addon, explicit), chosen_result)


def test_a_file_saved_now_keeps_the_new_default(addon, tmp_path):
    obj = _half_painted_sphere()
    painted = helpers.stepped_result(addon, obj)
    path = str(tmp_path / "new.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)

    obj = bpy.data.objects["Sphere"]
    assert obj.gauss_stylization.uncovered == 'UNSTYLED'
    assert not obj.gauss_stylization.is_property_set("uncovered")  # still the default, not written out
    assert np.array_equal(helpers.stepped_result(addon, obj), painted)


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


def _stamped_by_version_3(addon, name):
    """A Resolution Independent object with a Region of 0.5, as the add-on at settings version 3 read it
    from its file: stamped 3, the paint curve of version 4 never set (an older add-on's session)."""
    obj = _half_painted_sphere(name)
    obj.gauss_stylization.settings_version = 3
    assert obj.gauss_stylization.resolution_independent
    assert not obj.gauss_stylization.is_property_set("old_paint_curve")
    return obj


def test_an_object_stamped_by_an_earlier_version_is_brought_up_to_date_before_the_save(addon, tmp_path):
    """A file the add-on of version 3 opened, saved after an update to today's in the same session (or
    holding an object appended from such a file), keeps its objects' result: save_pre brings them up to
    date before it stamps them."""
    old = _stamped_by_version_3(addon, "Old")
    new = _half_painted_sphere("New")  # made in this session: stamp 0, today's rules
    path = str(tmp_path / "updated.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    old, new = bpy.data.objects["Old"].gauss_stylization, bpy.data.objects["New"].gauss_stylization
    assert old.old_paint_curve is True and old.settings_version == addon.settings.versioning.VERSION
    assert new.old_paint_curve is False and not new.is_property_set("old_paint_curve")


def test_a_run_brings_a_stamped_object_up_to_date_first(addon):
    """Stylizing such an object gives the result it had in its own file (the old curve), not today's."""
    today = _half_painted_sphere("Today")
    todays_result = helpers.stepped_result(addon, today)
    today.gauss_stylization.old_paint_curve = True
    old_curve_result = helpers.stepped_result(addon, today)
    assert np.abs(todays_result - old_curve_result).max() > 1e-4
    obj = _stamped_by_version_3(addon, "Appended")
    # Two objects built alike differ by rounding (1e-15), the two curves by far more.
    np.testing.assert_allclose(helpers.stepped_result(addon, obj), old_curve_result, rtol=0, atol=1e-9)
    assert obj.gauss_stylization.old_paint_curve is True


def test_replay_of_a_stamped_object_keeps_its_old_rule(addon):
    """Replay restores the object's settings when it ends: a stamped object is brought up to date
    before that snapshot, so its old curve is not overwritten with today's value."""
    obj = _half_painted_sphere("Appended")
    helpers.activate(obj)
    assert bpy.ops.object.gauss_stylize(iterations=4) == {'FINISHED'}
    obj.gauss_stylization.settings_version = 3  # as if appended from a file of settings version 3
    obj.gauss_stylization.property_unset("old_paint_curve")
    assert bpy.ops.object.gauss_replay() == {'FINISHED'}
    settings = obj.gauss_stylization
    assert settings.old_paint_curve is True and settings.settings_version == addon.settings.versioning.VERSION


def _dump_of_version(addon, obj, version):
    """to_dict's settings as the add-on at settings ``version`` wrote them: without the fields added or
    given a new default since."""
    data = addon.settings_io.to_dict(obj.gauss_stylization)
    for field in addon.settings.schema.OBJECT:
        if (field.added or 0) > version or (field.since or 0) > version:
            del data[field.name]
    return data


def test_a_whole_dump_of_an_earlier_version_is_filled_as_it_ran(addon):
    """as_saved: the fields a version did not have get what it ran with; a dump of today, or a partial
    set, is left as it is."""
    as_saved = addon.settings.versioning.as_saved
    obj = _half_painted_sphere()
    version_0 = _dump_of_version(addon, obj, 0)
    assert {"uncovered", "resolution_independent", "square_flat_regions", "bake_warmup_frames"}.isdisjoint(version_0)
    read = as_saved(version_0)
    assert read["uncovered"] == 'FIRST_SLOT' and read["resolution_independent"] is False
    assert read["weigh_finer_faces"] is False and read["old_paint_curve"] is False  # not without the setting
    assert read["square_flat_regions"] is False and read["bake_warmup_frames"] == 8  # added: their defaults
    read = as_saved(_dump_of_version(addon, obj, 3))  # Resolution Independent on, the old curve not yet
    assert read["old_paint_curve"] is True and read["weigh_finer_faces"] is False
    today = addon.settings_io.to_dict(obj.gauss_stylization)
    assert as_saved(today) == today and as_saved({"lam": 2.0}) == {"lam": 2.0}
    del version_0["lam"]
    assert as_saved(version_0) == version_0  # lacks a field every version had: partial


# The object settings of settings version 1 (2026-11-27), the first with a stamp: a field added since names
# its version (added=) or its old default (since=, before=), so that as_saved knows old dumps lack it.
VERSION_1_FIELDS = {
    "active_style_index", "admm_iterations", "avoid_self_intersections", "bake_filepath", "bake_frame_end",
    "bake_frame_start", "bake_scene_range", "bake_steps", "bake_warm_start", "cubic_lambda", "iterations",
    "keep_volume", "lam", "method", "output", "pin_group", "show_gauss_sphere", "styles", "tolerance",
    "use_modifiers"}


def test_every_field_added_since_version_1_says_when(addon):
    unmarked = {f.name for f in addon.settings.schema.OBJECT if f.added is None and f.since is None}
    assert unmarked == VERSION_1_FIELDS, (
        "a new object setting needs added=VERSION (or since/before if it changes a result): %s"
        % sorted(unmarked - VERSION_1_FIELDS))


def test_settings_an_earlier_version_saved_are_read_as_saved(addon, tmp_path):
    """A whole batch preset or a script's settings_json written before Other Faces existed stylizes as it
    did (First Style, without Resolution Independent); a partial preset keeps today's rules."""
    then = _half_painted_sphere("Then")
    _as_version_0_ran(then)
    then.gauss_stylization.uncovered = 'FIRST_SLOT'
    dump = _dump_of_version(addon, then, 0)
    helpers.activate(then)
    assert bpy.ops.object.gauss_stylize(iterations=8) == {'FINISHED'}
    preset = tmp_path / "old_preset.json"
    preset.write_text(json.dumps(dump))
    read = addon.bake.batch.read_preset(str(preset))
    assert read["uncovered"] == 'FIRST_SLOT' and read["resolution_independent"] is False
    partial = tmp_path / "partial.json"
    partial.write_text(json.dumps({"lam": 2.0}))
    assert addon.bake.batch.read_preset(str(partial)) == {"lam": 2.0}

    today = _half_painted_sphere("Today")
    helpers.activate(today)
    assert bpy.ops.object.gauss_stylize(iterations=8) == {'FINISHED'}
    now = _half_painted_sphere("Now")
    helpers.activate(now)
    assert bpy.ops.object.gauss_stylize(iterations=8, settings_json=json.dumps(dump)) == {'FINISHED'}
    settings = now.gauss_stylization
    assert settings.uncovered == 'FIRST_SLOT' and settings.resolution_independent is False
    np.testing.assert_allclose(helpers.coords(now), helpers.coords(then), rtol=0, atol=1e-9)
    assert np.abs(helpers.coords(now) - helpers.coords(today)).max() > 1e-4  # the dump's rules, not today's
    dump.pop("lam")  # not a field whose default changed: a script's error, as before
    with pytest.raises(RuntimeError, match="missing setting"):
        bpy.ops.object.gauss_stylize(iterations=8, settings_json=json.dumps(dump))
