"""Replay (object.gauss_replay, run/replay.py): a mesh's kept runs, live or scripted, are recorded in its
recipe (mesh/recipe_store.py, part of the .blend) and re-run from the rest shape bit for bit: the settings
each run started with, every change at its step (settings, pin targets a handle sets), its step count."""
import bpy
import numpy as np
import pytest

import helpers


def _suzanne():
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'CUBE')
    return obj


def _replay(obj):
    helpers.activate(obj)
    assert bpy.ops.object.gauss_replay() == {'FINISHED'}
    return helpers.coords(obj)


def test_two_kept_scripted_runs_replay_bit_for_bit(addon):
    obj = _suzanne()
    rest = helpers.coords(obj)
    assert not bpy.ops.object.gauss_replay.poll()  # nothing kept yet
    assert helpers.stylize(12, lam=4.0) == {'FINISHED'}
    first = helpers.coords(obj)
    obj.gauss_stylization.styles[0].preset = 'TETRAHEDRON'
    assert helpers.stylize(9, lam=9.0, keep_volume=True) == {'FINISHED'}
    kept = helpers.coords(obj)
    recipe = addon.run.replay.recipe(obj)
    assert [run["steps"] for run in recipe["runs"]] == [12, 9] and np.array_equal(recipe["rest"], rest)
    assert recipe["runs"][1]["settings"]["lam"] == 9.0 and recipe["runs"][0]["settings"]["lam"] == 4.0
    obj.gauss_stylization.lam = 2.0  # the settings now are not the runs'...
    assert np.array_equal(_replay(obj), kept) and not np.array_equal(kept, first)
    assert obj.gauss_stylization.lam == 2.0  # ... and stay the artist's after a replay
    again = addon.run.replay.recipe(obj)  # the replay recorded itself: the same recipe
    assert [r["result_fingerprint"] for r in again["runs"]] == [r["result_fingerprint"] for r in recipe["runs"]]
    # Reset takes the last run back, and out of the recipe: a replay then gives the first run's result.
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert np.array_equal(helpers.coords(obj), first)
    assert [run["steps"] for run in addon.run.replay.recipe(obj)["runs"]] == [12]
    assert np.array_equal(_replay(obj), first)


def test_a_live_run_with_a_lambda_change_and_handle_moves_replays_bit_for_bit(addon):
    obj = _suzanne()
    top = [v.index for v in obj.data.vertices if v.co.z > 0.6]
    helpers.add_group(obj, "Top", top)
    obj.gauss_stylization.pin_group = "Top"
    live = helpers.live_run([obj])
    session = live.sessions[0]
    targets = np.asarray(session.solver.pin_positions, np.float64)
    for tick in range(30):
        if tick == 8:
            obj.gauss_stylization.lam = 7.5  # typed into the sidebar mid-run
        if 12 <= tick < 20:  # a handle dragged up, a little every tick
            session.move_pins(targets + [0.0, 0.0, 0.02 * (tick - 11)])
        live.tick(budget=1e9)
    live.keep()
    kept = helpers.coords(obj)
    events = addon.run.replay.recipe(obj)["runs"][0]["events"]
    assert [e["step"] for e in events if "settings" in e] == [8] and sum("pins" in e for e in events) == 8
    obj.gauss_stylization.lam = 4.0
    assert np.array_equal(_replay(obj), kept)


def test_an_edit_between_runs_starts_a_new_recipe_from_the_edited_mesh(addon):
    obj = _suzanne()
    assert helpers.stylize(5) == {'FINISHED'}
    coords = helpers.coords(obj)
    coords[0] += 0.05  # an Edit Mode move
    helpers.mesh_io.write_vertex_coords(obj.data, coords)
    assert helpers.stylize(6) == {'FINISHED'}
    kept = helpers.coords(obj)
    recipe = addon.run.replay.recipe(obj)
    assert [run["steps"] for run in recipe["runs"]] == [6] and np.array_equal(recipe["rest"], coords)
    assert np.array_equal(_replay(obj), kept)


def test_a_shape_key_run_replays_from_the_basis(addon):
    obj = _suzanne()
    basis = helpers.coords(obj)
    assert helpers.stylize(7, output='SHAPE_KEY') == {'FINISHED'}
    key = obj.data.shape_keys.key_blocks["Gauss Stylized"]
    kept = helpers.mesh_io.read_key_coords(key)
    assert helpers.stylize(7, output='SHAPE_KEY', lam=8.0) == {'FINISHED'}  # again from the basis
    assert [run["steps"] for run in addon.run.replay.recipe(obj)["runs"]] == [7]
    second = helpers.mesh_io.read_key_coords(key)
    assert not np.array_equal(second, kept)
    helpers.activate(obj)
    assert bpy.ops.object.gauss_replay() == {'FINISHED'}
    assert np.array_equal(helpers.mesh_io.read_key_coords(key), second)
    assert np.array_equal(helpers.mesh_io.read_key_coords(obj.data.shape_keys.reference_key), basis)


def test_a_replay_that_fails_leaves_mesh_and_recipe_as_they_were(addon, monkeypatch):
    obj = _suzanne()
    assert helpers.stylize(5) == {'FINISHED'}
    kept, recipe = helpers.coords(obj), obj.data[addon.mesh.recipe_store.KEY]

    def broken(self):
        raise addon.errors.SettingsError("broken on purpose")
    monkeypatch.setattr(addon.run.session.Session, "step", broken)
    helpers.activate(obj)
    with pytest.raises(RuntimeError, match="broken on purpose"):
        bpy.ops.object.gauss_replay()
    assert np.array_equal(helpers.coords(obj), kept) and obj.data[addon.mesh.recipe_store.KEY] == recipe


def test_runs_with_use_modifiers_end_the_recipe(addon):
    obj = _suzanne()
    assert helpers.stylize(5) == {'FINISHED'}
    assert bpy.ops.object.gauss_replay.poll()
    obj.modifiers.new("Bend", 'SIMPLE_DEFORM')
    assert helpers.stylize(5, use_modifiers=True) == {'FINISHED'}
    assert addon.run.replay.recipe(obj) is None and not bpy.ops.object.gauss_replay.poll()


def test_the_recipe_is_saved_with_the_file_and_replays_after_reopening(addon, tmp_path):
    obj = _suzanne()
    assert helpers.stylize(6, lam=6.0) == {'FINISHED'}
    kept, name = helpers.coords(obj), obj.name
    path = str(tmp_path / "recipe.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    obj = bpy.data.objects[name]
    assert [run["steps"] for run in addon.run.replay.recipe(obj)["runs"]] == [6]
    assert np.array_equal(_replay(obj), kept)


def test_a_region_repainted_mid_run_replays_bit_for_bit(addon):
    # The artist paints the Region in Weight Paint during the run; the recipe holds the new weights at
    # the step the run read them, and the weights the object has after the run are not the replay's.
    obj = _suzanne()
    rest = helpers.coords(obj)
    helpers.add_group(obj, "Paint", np.flatnonzero(rest[:, 2] > 0.0), weight=0.3)
    obj.gauss_stylization.styles[0].vertex_group = "Paint"
    live = helpers.live_run_with_a_repaint(obj, "Paint", 0.9, ticks_before=6, ticks_after=10)
    live.keep()
    kept = helpers.coords(obj)
    events = addon.run.replay.recipe(obj)["runs"][0]["events"]
    assert [(e["step"], e["repainted"]) for e in events if "repainted" in e] == [(6, ["REGIONS"])]
    obj.vertex_groups["Paint"].add(list(range(len(rest))), 0.1, 'REPLACE')  # painted again since
    assert np.array_equal(_replay(obj), kept)


def test_a_mesh_whose_vertex_count_changed_is_refused_and_left_alone(addon):
    import bmesh
    obj = _suzanne()
    assert helpers.stylize(5) == {'FINISHED'}
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    bmesh.ops.delete(bm, geom=[bm.verts[0]], context="VERTS")
    bm.to_mesh(obj.data)
    bm.free()
    before = helpers.coords(obj)
    helpers.activate(obj)
    with pytest.raises(RuntimeError, match="vertex count changed"):
        bpy.ops.object.gauss_replay()
    assert np.array_equal(helpers.coords(obj), before)
