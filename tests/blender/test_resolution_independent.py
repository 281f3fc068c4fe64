"""Resolution Independent: on for new objects, off for objects of files saved before it existed (their
result is kept, settings/versioning.py), and passed to the solver (docs/resolution.md). Its rule before
settings version 3 (weigh_finer_faces) stays with the files and recipes made under it."""

import bpy
import numpy as np

import helpers

FIELD = "resolution_independent"


def test_new_objects_start_with_it_on_and_the_solver_gets_it(addon):
    assert addon.native.facts().defaults[FIELD] is False  # the solver's default: the paper's method
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE')
    assert obj.gauss_stylization.resolution_independent is True
    for value in (True, False):
        obj.gauss_stylization.resolution_independent = value
        run = addon.run.session.Session(obj)
        try:
            assert run.solver.resolution_independent is value
        finally:
            run.cancel()


def test_objects_saved_before_the_setting_existed_open_with_it_off(addon, tmp_path):
    assert addon.settings.schema.field(addon.settings.schema.OBJECT, FIELD).since == 2
    for version in (0, 1):
        helpers.clear_scene()
        with_slot, without = helpers.suzanne(levels=0), helpers.uv_sphere(8, 4)
        with_slot.name, without.name = "Slot", "NoSlot"
        helpers.add_slot(with_slot, 'CUBE')
        without.gauss_stylization.lam = 3.0  # settings, but no slot yet: Stylize adds one
        path = str(tmp_path / ("v%d.blend" % version))
        helpers.save_as_version(addon, path, version, FIELD, OLD_RULE, "old_paint_curve")
        helpers.clear_scene()
        bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
        for name in ("Slot", "NoSlot"):
            settings = bpy.data.objects[name].gauss_stylization
            assert settings.resolution_independent is False, (version, name)
            assert settings.weigh_finer_faces is False, (version, name)  # the old rule only with the setting
            assert settings.old_paint_curve is False, (version, name)  # so the old paint curve
            assert settings.settings_version == addon.settings.versioning.VERSION
        # An object made now, in that file, starts with it on.
        fresh = helpers.uv_sphere(8, 4)
        helpers.add_slot(fresh, 'CUBE')
        assert fresh.gauss_stylization.resolution_independent is True


def test_a_file_saved_now_keeps_each_object_s_value(addon, tmp_path):
    on, off = helpers.suzanne(levels=0), helpers.uv_sphere(8, 4)
    on.name, off.name = "On", "Off"
    for obj in (on, off):
        helpers.add_slot(obj, 'CUBE')
    off.gauss_stylization.resolution_independent = False
    path = str(tmp_path / "now.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    assert bpy.data.objects["On"].gauss_stylization.resolution_independent is True
    assert bpy.data.objects["Off"].gauss_stylization.resolution_independent is False


def test_it_changes_the_result(addon):
    results = {}
    for value in (False, True):
        obj = helpers.suzanne(levels=1)
        helpers.add_slot(obj, 'CUBE')
        bpy.context.view_layer.objects.active = obj
        assert helpers.stylize(20, resolution_independent=value) == {'FINISHED'}
        results[value] = helpers.coords(obj)
        helpers.clear_scene()
    assert np.abs(results[True] - results[False]).max() > 1e-4


OLD_RULE = "weigh_finer_faces"


def _tetrahedron_suzanne():
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'TETRAHEDRON')
    return obj


def test_objects_saved_under_version_2_keep_its_rule(addon, tmp_path):
    """A file saved at settings version 2 (Resolution Independent on, its rule then weighing every face)
    opens with that rule and stylizes as it did; new objects get today's."""
    assert addon.native.facts().defaults[OLD_RULE] is False
    assert addon.settings.schema.field(addon.settings.schema.OBJECT, OLD_RULE).since == 3
    obj = _tetrahedron_suzanne()
    obj.name = "Old"
    off = _tetrahedron_suzanne()
    off.name = "Off"
    off.gauss_stylization.resolution_independent = False
    assert obj.gauss_stylization.resolution_independent is True and obj.gauss_stylization.weigh_finer_faces is False
    results = {}
    for rule in (True, False):
        obj.gauss_stylization.weigh_finer_faces = rule
        run = addon.run.session.Session(obj)
        run.step(15)
        results[rule] = run.result.copy()
        run.cancel()
    assert not np.array_equal(results[True], results[False])
    path = str(tmp_path / "v2.blend")
    helpers.save_as_version(addon, path, 2, OLD_RULE, "old_paint_curve")
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    obj = bpy.data.objects["Old"]
    assert obj.gauss_stylization.weigh_finer_faces is True
    assert obj.gauss_stylization.old_paint_curve is True  # version 2 painted as version 3 did
    run = addon.run.session.Session(obj)
    run.step(15)
    assert np.array_equal(run.result, results[True])
    run.cancel()
    # Without Resolution Independent the old rules would change nothing: they are not written out there.
    assert bpy.data.objects["Off"].gauss_stylization.weigh_finer_faces is False
    assert bpy.data.objects["Off"].gauss_stylization.old_paint_curve is False
    # The Solver panel shows the old rule where it is in effect, so that the artist can untick it.
    field = addon.settings.schema.field(addon.settings.schema.OBJECT, OLD_RULE)
    assert field.panel is addon.settings.fields.Panel.SOLVER and field.shown(obj.gauss_stylization)
    # The cubic method does not read it: the row is not shown there.
    obj.gauss_stylization.method = addon.settings.schema.CUBIC
    assert not field.shown(obj.gauss_stylization)
    fresh = _tetrahedron_suzanne()
    assert fresh.gauss_stylization.weigh_finer_faces is False and not field.shown(fresh.gauss_stylization)


def test_a_recipe_recorded_under_version_2_replays_with_its_rule(addon):
    """Replay of a run whose recipe predates the field (no weigh_finer_faces in its settings) uses the
    rule it ran with, whatever the object says now."""
    helpers.replays_with_the_old_rule(addon, _tetrahedron_suzanne, OLD_RULE, 15)
