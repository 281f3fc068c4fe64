"""Stylize on several selected meshes: each with its own settings and
solver, skipped objects named, one undo step; the live run's ticks without a window."""

import json

import bpy
import numpy as np
import pytest

import helpers


def _pair(levels=1):
    """Two Suzannes side by side, 'B' active, both selected."""
    a = helpers.suzanne(levels=levels)
    a.name = "A"
    b = helpers.suzanne(levels=levels)
    b.name = "B"
    b.location.x = 3.0
    a.select_set(True)
    return a, b


def _alone(obj, iterations):
    """What stylizing a copy of ``obj`` on its own gives (same mesh, same settings)."""
    copy = obj.copy()
    copy.data = obj.data.copy()
    bpy.context.scene.collection.objects.link(copy)
    helpers.activate(copy)
    assert bpy.ops.object.gauss_stylize(iterations=iterations) == {'FINISHED'}
    result = helpers.coords(copy)
    bpy.data.objects.remove(copy)
    return result


def test_each_selected_mesh_runs_with_its_own_settings_and_solver():
    a, b = _pair()
    helpers.add_slot(a, 'OCTAHEDRON', sigma=6.0)
    helpers.add_slot(b, 'CUBE')
    b.gauss_stylization.lam = 8.0
    expected = {obj.name: _alone(obj, 10) for obj in (a, b)}
    helpers.activate(b)
    a.select_set(True)
    assert bpy.ops.object.gauss_stylize(iterations=10) == {'FINISHED'}
    for obj in (a, b):
        assert np.array_equal(helpers.coords(obj), expected[obj.name]), obj.name


def test_objects_without_a_style_get_the_default_one():
    a, b = _pair(levels=0)
    helpers.add_slot(b, 'TETRAHEDRON')
    assert helpers.stylize(3) == {'FINISHED'}
    assert [s.preset for s in a.gauss_stylization.styles] == ['CUBE']
    assert [s.preset for s in b.gauss_stylization.styles] == ['TETRAHEDRON']


def test_an_object_that_cannot_be_stylized_is_skipped_and_named(capfd):
    a, b = _pair(levels=0)
    a_start, b_start = helpers.coords(a), helpers.coords(b)
    a.gauss_stylization.pin_group = "Nails"  # no such group
    assert helpers.stylize(5) == {'FINISHED'}
    assert "Skipped 'A'" in capfd.readouterr().out
    assert np.array_equal(helpers.coords(a), a_start) and len(a.gauss_stylization.styles) == 0
    assert not np.array_equal(helpers.coords(b), b_start)


def test_when_none_can_be_stylized_the_error_names_each():
    a, b = _pair(levels=0)
    a.gauss_stylization.pin_group = "Nails"
    b.gauss_stylization.pin_group = "Claws"
    with pytest.raises(RuntimeError, match=r"'B': Pin Group: there is no vertex group 'Claws'.*'A': .*'Nails'"):
        bpy.ops.object.gauss_stylize(iterations=5)


def test_objects_sharing_a_mesh_are_stylized_once(capfd):
    a, b = _pair(levels=0)
    b.data = a.data
    expected = _alone(a, 5)
    helpers.activate(b)
    a.select_set(True)
    assert bpy.ops.object.gauss_stylize(iterations=5) == {'FINISHED'}
    assert "shares its mesh" in capfd.readouterr().out
    assert np.array_equal(helpers.coords(a), expected)  # 5 steps, not 10


def test_one_undo_step_gives_every_object_back():
    a, b = _pair()
    starts = helpers.coords(a), helpers.coords(b)
    bpy.ops.ed.undo_push(message="Before")
    assert bpy.ops.object.gauss_stylize('EXEC_DEFAULT', True, iterations=5) == {'FINISHED'}  # undo=True
    assert not np.array_equal(helpers.coords(bpy.data.objects["A"]), starts[0])
    bpy.ops.ed.undo()
    assert np.array_equal(helpers.coords(bpy.data.objects["A"]), starts[0])
    assert np.array_equal(helpers.coords(bpy.data.objects["B"]), starts[1])


def test_redo_panel_repeats_every_object_with_its_settings(addon):
    a, b = _pair(levels=0)
    helpers.add_slot(a, 'CUBE', sigma=9.0)
    helpers.add_slot(b, 'OCTAHEDRON', sigma=3.0)
    ended_with = addon.settings_io.objects_to_json([b, a])
    assert set(json.loads(ended_with)) == {"objects"}
    a.gauss_stylization.styles[0].sigma = b.gauss_stylization.styles[0].sigma = 5.0
    assert bpy.ops.object.gauss_stylize(iterations=2, settings_json=ended_with) == {'FINISHED'}
    assert (a.gauss_stylization.styles[0].sigma, b.gauss_stylization.styles[0].sigma) == (9.0, 3.0)


# -- the live run's ticks (the modal operator drives these; see windowed_live_run.py) --------

def test_live_ticks_step_every_object_in_turn_within_the_budget(addon):
    a, b = _pair(levels=0)
    live = helpers.live_run([b, a])
    live.tick(budget=1e9)
    assert [s.steps for s in live.sessions] == [1, 1]
    for expected in ([2, 1], [2, 2], [3, 2]):  # a budget used up by one step: round-robin
        live.tick(budget=0.0)
        assert [s.steps for s in live.sessions] == expected
    live.cancel()


def test_live_cancel_restores_all_and_keep_keeps_all(addon):
    a, b = _pair(levels=0)
    starts = helpers.coords(a), helpers.coords(b)
    live = helpers.live_run([b, a])
    for _ in range(4):
        live.tick()
    assert not np.array_equal(helpers.coords(a), starts[0])
    live.cancel()
    assert np.array_equal(helpers.coords(a), starts[0]) and np.array_equal(helpers.coords(b), starts[1])
    live = helpers.live_run([b, a])
    live.tick()
    live.keep()
    assert addon.mesh.rest_store.has_capture(a.data) and addon.mesh.rest_store.has_capture(b.data)


def test_live_run_goes_on_without_a_deleted_object(addon):
    a, b = _pair(levels=0)
    live = helpers.live_run([b, a])
    mesh, a_start = a.data, helpers.coords(a)
    live.tick()
    bpy.data.objects.remove(a)
    outcome = live.tick()
    assert [(s.name, why) for s, why in outcome.stopped] == [("A", "the object was deleted or its mesh replaced")]
    assert [s.obj for s in live.sessions] == [b] and live.sessions[0].steps == 2
    out = np.empty((len(mesh.vertices), 3), np.float32)
    mesh.vertices.foreach_get("co", out.reshape(-1))
    assert np.array_equal(out, a_start)  # A's mesh was restored when it left the run
    live.cancel()


def test_live_run_cancelled_while_preparing_changes_nothing(addon):
    a, b = _pair(levels=0)
    starts = helpers.coords(a), helpers.coords(b)
    planned = addon.run.targets.plan_objects(helpers.Reports(), [b, a])
    live = addon.run.live_run.LiveRun(planned)
    live.cancel()
    assert live.setup is None
    assert len(a.gauss_stylization.styles) == 0 and len(b.gauss_stylization.styles) == 0
    assert np.array_equal(helpers.coords(a), starts[0]) and np.array_equal(helpers.coords(b), starts[1])


def test_each_object_of_a_live_run_finds_its_own_session(addon):
    # For features that work on the object under the mouse (pin handles, the sphere overlay).
    a, b = _pair(levels=0)
    live = helpers.live_run([b, a])

    class Run:
        sessions = live.sessions

        def stop(self, context, keep):
            live.cancel()

    run = Run()
    addon.run.runs.start([b, a], run)
    try:
        assert addon.run.runs.session_of(a).obj == a and addon.run.runs.session_of(b).obj == b
        assert [s.obj for s in addon.run.runs.live_sessions()] == [b, a]
        assert addon.run.runs.session_of(helpers.uv_sphere()) is None
    finally:
        addon.run.runs.forget(run)
        live.cancel()
