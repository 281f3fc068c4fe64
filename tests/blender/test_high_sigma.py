"""High sigma: above gauss_core.PAPER_STEP_MAX_SIGMA the solver takes a face's normal step on the sphere
for styles whose bumps stand apart (gauss_core.Style.trust_region_step), where the paper's step never let
a run settle. Objects and recipes saved before (settings version 4 and
earlier) with such a slot keep the paper's step (paper_step_any_sigma), so they stylize and replay as
they did; below the limit nothing changes and nothing is written out."""

import bpy
import numpy as np

import helpers

FIELD = "paper_step_any_sigma"


def _sphere(name, sigma, preset='CUBE'):
    obj = helpers.uv_sphere()
    obj.name = name
    helpers.add_slot(obj, preset, sigma=sigma)
    return obj


def test_a_sharp_slot_settles_where_the_papers_step_did_not(addon):
    obj = _sphere("Sharp", 16.0)
    assert obj.gauss_stylization.paper_step_any_sigma is False
    for rule, settles in ((False, True), (True, False)):
        obj.gauss_stylization.paper_step_any_sigma = rule
        run = addon.run.session.Session(obj)
        try:
            run.step_until(300)
            assert run.converged is settles, (rule, run.reldv)
        finally:
            run.cancel()


def test_objects_saved_under_version_4_keep_the_papers_step(addon, tmp_path):
    versioning = addon.settings.versioning
    schema = addon.settings.schema
    field = schema.field(schema.OBJECT, FIELD)
    assert field.since == 5 <= versioning.VERSION
    obj = _sphere("Old", 12.0)
    _sphere("Mild", 8.0)
    _sphere("Close", 12.0, 'ICOSAHEDRON')  # its bumps overlap: the paper's step at 12 either way
    results = {}
    for rule in (True, False):
        obj.gauss_stylization.paper_step_any_sigma = rule
        results[rule] = helpers.stepped_result(addon, obj)
    assert np.abs(results[True] - results[False]).max() > 1e-4
    helpers.save_as_version(addon, str(tmp_path / "v4.blend"), 4, FIELD)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "v4.blend"), load_ui=False)
    obj = bpy.data.objects["Old"]
    assert obj.gauss_stylization.paper_step_any_sigma is True
    np.testing.assert_array_equal(helpers.stepped_result(addon, obj), results[True])
    # At sigma 8 the step was the paper's either way: nothing is written out, nothing shown.
    mild = bpy.data.objects["Mild"].gauss_stylization
    assert mild.paper_step_any_sigma is False and not field.shown(mild)
    close = bpy.data.objects["Close"].gauss_stylization
    assert close.paper_step_any_sigma is False and not field.shown(close)
    # The Solver panel shows the old step where it acts, so that the artist can untick it.
    assert field.panel is addon.settings.fields.Panel.SOLVER and field.shown(obj.gauss_stylization)
    obj.gauss_stylization.method = schema.CUBIC  # the cubic method has no normal step
    assert not field.shown(obj.gauss_stylization)
    obj.gauss_stylization.method = 'GAUSS'
    obj.gauss_stylization.styles[0].preset = 'SHEET_METAL'  # its sigma of 16 keeps the paper's step
    assert not field.shown(obj.gauss_stylization)
    fresh = _sphere("New", 12.0)
    assert fresh.gauss_stylization.paper_step_any_sigma is False and not field.shown(fresh.gauss_stylization)


def test_a_recipe_recorded_under_version_4_replays_with_the_papers_step(addon):
    helpers.replays_with_the_old_rule(addon, lambda: _sphere("Old", 12.0), FIELD, 8)
