"""Keep Volume (settings.keep_volume): the checkbox reaches the solver when a run
starts and when it is changed during a live run."""

import bpy
import pytest

import helpers

BUNNY = "bunny/bunny_watertight_34834.obj"


def _volume(obj):
    return helpers.scene_kit.enclosed_volume(helpers.coords(obj), helpers.triangles(obj)[0])


def test_keep_volume_is_off_by_default_and_the_solver_default(addon):
    obj = helpers.suzanne(levels=0)
    assert obj.gauss_stylization.keep_volume is False
    assert addon.native.facts().defaults["keep_volume"] is False


def test_the_watertight_bunny_keeps_its_volume_with_keep_volume(addon):
    ratios = {}
    for keep in (False, True):
        obj = helpers.import_obj(BUNNY)
        rest = _volume(obj)
        assert helpers.stylize(100, lam=4.0, keep_volume=keep) == {'FINISHED'}
        ratios[keep] = _volume(obj) / rest
        bpy.data.objects.remove(obj)
    print("watertight bunny, 100 steps at lambda 4: volume kept %.4f without Keep Volume, %.6f with"
          % (ratios[False], ratios[True]))
    assert ratios[True] == pytest.approx(1.0, abs=0.01)
    assert ratios[False] < 0.95  # it shrinks without


def test_keep_volume_changed_during_a_live_run_reaches_the_solver(addon):
    obj = helpers.uv_sphere(24, 12)
    rest = _volume(obj)
    settings = obj.gauss_stylization
    addon.run.session.ensure_style_slot(settings)
    settings.lam = 10.0
    run = addon.run.session.Session(obj)
    run.step(20)
    shrunk = _volume(obj) / rest
    settings.keep_volume = True
    assert run.sync_settings() is None and run.solver.keep_volume
    run.step(1)
    kept = _volume(obj) / rest
    run.keep()
    print("sphere volume after 20 steps: %.4f of its rest volume; one step with Keep Volume: %.6f" % (shrunk, kept))
    assert abs(shrunk - 1.0) > 0.01 and kept == pytest.approx(1.0, abs=1e-4)
