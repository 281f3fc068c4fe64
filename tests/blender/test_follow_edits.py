"""Follow Edits (the object setting ``follow_edits``, run/follow.py): the copy a New Object run kept is
made again from its source when the source changes, off the main thread, and ends up exactly what
Replay of the copy (run/rerun.py) and a new New Object run from the edited source give.

No timer runs while a test does: the depsgraph handler is driven by view_layer.update(), the quiet
period by follow._tick() with QUIET_SECONDS at 0, and the workers are waited for by follow.settle()."""
import bmesh
import bpy
import numpy as np
import pytest
from mathutils import Vector

import helpers

STEPS = 8


@pytest.fixture
def follow(addon, monkeypatch):
    module = addon.run.follow
    monkeypatch.setattr(module, "QUIET_SECONDS", 0.0)
    yield module
    module.settle(30.0)
    for name in list(module._followers):
        module._drop(name)
    module._dirty.clear()


def _kept_copy(addon, follow_edits=True, **settings):
    """A Suzanne whose New Object run of STEPS steps was kept, and its copy (Follow Edits as given)."""
    source = helpers.suzanne(levels=1)
    helpers.add_slot(source, 'CUBE')
    source.gauss_stylization.follow_edits = follow_edits
    assert helpers.stylize(STEPS, output='NEW_OBJECT', lam=4.0, **settings) == {'FINISHED'}
    copy = bpy.data.objects[source.name + addon.settings.schema.NEW_OBJECT_SUFFIX]
    assert copy.gauss_stylization.follow_edits == follow_edits
    return source, copy


def _edit(source, offset=(0.0, 0.0, 0.05), count=40):
    """Move the source's first ``count`` vertices, as an Edit Mode move does, and let the depsgraph
    tell the handlers."""
    coords = helpers.coords(source)
    coords[:count] += np.asarray(offset, np.float32)
    helpers.mesh_io.write_vertex_coords(source.data, coords)
    helpers.mesh_io.tag_changed(source.data)
    bpy.context.view_layer.update()


def _edit_in_edit_mode(source, offset, count):
    """Enter Edit Mode on the source and move its first ``count`` vertices in the edit mesh, as a grab
    there does (the mesh's own vertices stay stale until Object Mode)."""
    source.hide_set(False)
    helpers.activate(source)
    bpy.ops.object.mode_set(mode='EDIT')
    edit = bmesh.from_edit_mesh(source.data)
    for vertex in list(edit.verts)[:count]:
        vertex.co += Vector(offset)
    bmesh.update_edit_mesh(source.data)
    bpy.context.view_layer.update()


def _subdivide_some_edges(source):
    """Change the source's topology (its first 40 edges cut in two) and let the depsgraph tell the handlers."""
    bm = bmesh.new()
    bm.from_mesh(source.data)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:40], cuts=1, use_grid_fill=True)
    bm.to_mesh(source.data)
    bm.free()
    source.data.update()
    bpy.context.view_layer.update()


def _replayed(copy):
    """What Replay of the copy gives (Follow Edits off meanwhile, so nothing else writes)."""
    was = copy.gauss_stylization.follow_edits
    copy.gauss_stylization.follow_edits = False
    helpers.activate(copy)
    assert bpy.ops.object.gauss_replay() == {'FINISHED'}
    result = helpers.coords(copy)
    copy.gauss_stylization.follow_edits = was
    return result


def _new_run_from(source):
    """A fresh New Object run from the source as it is now, with the kept run's settings."""
    source.hide_set(False)
    helpers.activate(source)
    assert helpers.stylize(STEPS, output='NEW_OBJECT', follow_edits=False) == {'FINISHED'}
    fresh = bpy.context.active_object
    assert fresh.name.startswith(source.name + "_stylized.")
    return helpers.coords(fresh)


def test_the_copy_follows_an_edit_bit_for_bit_with_replay_and_a_new_run(addon, follow):
    source, copy = _kept_copy(addon)
    kept = helpers.coords(copy)
    finished = follow.stats["finished"]
    _edit(source)
    assert copy.name in follow._dirty  # the handler saw the source change
    assert follow.settle(60.0)
    followed = helpers.coords(copy)
    assert follow.stats["finished"] == finished + 1
    assert not np.array_equal(followed, kept)
    assert follow.status(copy).startswith("Up to date")
    assert np.array_equal(followed, _new_run_from(source))
    assert np.array_equal(followed, _replayed(copy))


def test_an_unchanged_source_re_run_gives_the_kept_result(addon, follow):
    source, copy = _kept_copy(addon)
    kept = helpers.coords(copy)
    follow._mark([copy.name], force=True)  # as after an undo: re-run though the source reads as before
    assert follow.settle(60.0)
    assert np.array_equal(helpers.coords(copy), kept)
    assert np.array_equal(_replayed(copy), kept)


def test_quick_edits_coalesce_into_one_solve(addon, follow):
    source, copy = _kept_copy(addon)
    started, finished = follow.stats["started"], follow.stats["finished"]
    for _ in range(5):  # five edits before the source is still
        _edit(source, (0.01, 0.0, 0.0))
    assert follow.settle(60.0)
    assert (follow.stats["started"], follow.stats["finished"]) == (started + 1, finished + 1)
    assert np.array_equal(helpers.coords(copy), _replayed(copy))


def test_a_newer_edit_supersedes_the_job_running_and_a_preview_shows_first(addon, follow):
    source, copy = _kept_copy(addon)
    kept = helpers.coords(copy)
    before = helpers.coords(source)
    previews, started = follow.stats["previews"], follow.stats["started"]
    _edit(source, (0.0, 0.0, 0.05))
    follow._tick()  # the quiet period is over: a job starts, the preview shows at once
    assert follow.stats["started"] == started + 1 and follow.stats["previews"] == previews + 1
    moved = helpers.coords(source) - before
    np.testing.assert_array_equal(helpers.coords(copy), kept + moved)
    _edit(source, (0.0, 0.03, 0.0))  # while it runs
    assert follow.settle(60.0)
    assert follow.stats["started"] == started + 2
    assert np.array_equal(helpers.coords(copy), _replayed(copy))


def test_it_never_follows_its_own_updates(addon, follow):
    source, copy = _kept_copy(addon)
    _edit(source)
    assert follow.settle(60.0)
    started = follow.stats["started"]
    for _ in range(3):  # the copy written and every depsgraph update since: nothing starts
        bpy.context.view_layer.update()
        helpers.mesh_io.tag_changed(copy.data)
        bpy.context.view_layer.update()
        follow._tick()
        assert follow.settle(60.0)
    assert follow.stats["started"] == started and not follow._dirty


def test_turning_it_off_stops_following_and_on_catches_up(addon, follow):
    source, copy = _kept_copy(addon)
    kept = helpers.coords(copy)
    copy.gauss_stylization.follow_edits = False
    started = follow.stats["started"]
    _edit(source)
    assert not follow._dirty and follow.settle(60.0)
    assert follow.stats["started"] == started and np.array_equal(helpers.coords(copy), kept)
    assert follow.status(copy) == ""
    copy.gauss_stylization.follow_edits = True  # catches up with the edit made meanwhile
    assert follow.settle(60.0)
    assert follow.stats["started"] == started + 1
    assert np.array_equal(helpers.coords(copy), _replayed(copy))


def test_a_topology_change_re_runs_from_scratch(addon, follow):
    source, copy = _kept_copy(addon)
    _subdivide_some_edges(source)
    assert follow.settle(60.0)
    assert "from scratch" in follow.status(copy)
    assert len(copy.data.vertices) == len(source.data.vertices)
    followed = helpers.coords(copy)
    assert np.isfinite(followed).all()
    assert np.array_equal(followed, _replayed(copy))
    assert np.array_equal(followed, _new_run_from(source))


def test_a_topology_change_that_drops_a_vertex_group_runs_without_it(addon, follow):
    source = helpers.suzanne(levels=1)
    helpers.add_slot(source, 'CUBE')
    helpers.add_group(source, "Top", [v.index for v in source.data.vertices if v.co.z > 0.6])
    source.gauss_stylization.follow_edits = True
    assert helpers.stylize(STEPS, output='NEW_OBJECT', pin_group="Top") == {'FINISHED'}
    copy = bpy.data.objects[source.name + "_stylized"]
    source.vertex_groups.remove(source.vertex_groups["Top"])
    bm = bmesh.new()
    bm.from_mesh(source.data)
    bm.faces.ensure_lookup_table()
    bmesh.ops.delete(bm, geom=[bm.faces[0]], context='FACES_ONLY')
    bm.to_mesh(source.data)
    bm.free()
    source.data.update()
    bpy.context.view_layer.update()
    assert follow.settle(60.0)
    assert "without the vertex group 'Top'" in follow.status(copy)
    assert len(copy.data.polygons) == len(source.data.polygons)
    assert np.isfinite(helpers.coords(copy)).all()


def test_an_edit_mode_edit_is_followed(addon, follow):
    source, copy = _kept_copy(addon)
    _edit_in_edit_mode(source, (0.0, 0.0, 0.05), count=30)
    assert copy.name in follow._dirty
    assert follow.settle(60.0)
    followed = helpers.coords(copy)
    bpy.ops.object.mode_set(mode='OBJECT')  # the edit mesh written to the mesh: Replay reads it
    assert np.array_equal(followed, _replayed(copy))


def test_use_modifiers_follows_a_shape_key(addon, follow):
    source = helpers.suzanne(levels=1)
    helpers.add_slot(source, 'CUBE')
    source.shape_key_add(name="Basis")
    key = source.shape_key_add(name="Lift")
    key.data[0].co.z += 0.3
    key.value = 0.0
    source.gauss_stylization.follow_edits = True
    assert helpers.stylize(STEPS, output='NEW_OBJECT', use_modifiers=True) == {'FINISHED'}
    copy = bpy.data.objects[source.name + "_stylized"]
    kept = helpers.coords(copy)
    key.value = 1.0
    bpy.context.view_layer.update()
    assert follow.settle(60.0)
    followed = helpers.coords(copy)
    assert not np.array_equal(followed, kept)
    assert np.array_equal(followed, _replayed(copy))


def test_a_deleted_source_stops_it_cleanly(addon, follow):
    source, copy = _kept_copy(addon)
    kept = helpers.coords(copy)
    _edit(source)
    follow._tick()  # a job runs
    bpy.data.objects.remove(source)
    assert follow.settle(60.0)  # its result is written: it was made from the source as it was
    follow._mark([copy.name], force=True)
    assert follow.settle(60.0)
    assert "was deleted" in follow.status(copy)
    assert np.isfinite(helpers.coords(copy)).all() and len(helpers.coords(copy)) == len(kept)
    bpy.context.view_layer.update()
    helpers.activate(copy)
    assert not bpy.ops.object.gauss_replay.poll()


def test_a_deleted_copy_stops_its_job(addon, follow):
    source, copy = _kept_copy(addon)
    name = copy.name
    _edit(source)
    follow._tick()
    bpy.data.objects.remove(copy)
    assert follow.settle(60.0)
    assert name not in follow._followers


def _live_changes(source, targets):
    """A live run of ``source`` (New Object output) with what an artist changes while it runs: Lambda
    typed into the sidebar at tick 4, and a handle dragged to ``targets`` (its pins' positions, a
    little further each tick) over ticks 6 to 11; kept. Returns the copy it made."""
    before = set(bpy.data.objects)
    live = helpers.live_run([source])
    session = live.sessions[0]
    for tick in range(16):
        if tick == 4:
            source.gauss_stylization.lam = 7.5
        if 6 <= tick < 12:
            session.move_pins(targets + [0.0, 0.0, 0.02 * (tick - 5)])
        live.tick(budget=1e9)
    live.keep()
    made = set(bpy.data.objects) - before
    assert len(made) == 1
    return made.pop()


def _source_with_a_handle():
    source = helpers.suzanne(levels=1)
    helpers.add_slot(source, 'CUBE')
    top = [v.index for v in source.data.vertices if v.co.z > 0.6]
    helpers.add_group(source, "Top", top)
    source.gauss_stylization.pin_group = "Top"
    source.gauss_stylization.output = 'NEW_OBJECT'
    source.gauss_stylization.follow_edits = True
    return source, helpers.coords(source)[top].astype(np.float64)


def test_a_run_with_changes_while_it_ran_is_made_again_bit_for_bit(addon, follow):
    source, targets = _source_with_a_handle()
    copy = _live_changes(source, targets)
    kept = helpers.coords(copy)
    events = follow_store_events(addon, copy)
    assert sum("settings" in e for e in events) == 1 and sum("pins" in e for e in events) == 6
    follow._mark([copy.name], force=True)  # as after an undo: re-run though the source reads as before
    assert follow.settle(60.0)
    assert follow.status(copy).startswith("Up to date")
    assert np.array_equal(helpers.coords(copy), kept)
    assert np.array_equal(_replayed(copy), kept)


def test_an_edit_is_followed_with_the_runs_changes_made_again(addon, follow):
    # The edit moves vertices away from the handle; the followed copy is what the same live run, with the
    # same Lambda change and the handle dragged to the same places, gives on the edited source.
    source, targets = _source_with_a_handle()
    copy = _live_changes(source, targets)
    kept = helpers.coords(copy)
    low = np.flatnonzero(helpers.coords(source)[:, 2] < -0.3)
    coords = helpers.coords(source)
    coords[low] += np.float32(0.05)
    helpers.mesh_io.write_vertex_coords(source.data, coords)
    helpers.mesh_io.tag_changed(source.data)
    bpy.context.view_layer.update()
    assert follow.settle(60.0)
    followed = helpers.coords(copy)
    assert not np.array_equal(followed, kept) and np.isfinite(followed).all()
    source.gauss_stylization.lam = 4.0  # as it was when the kept run started
    source.gauss_stylization.follow_edits = False
    fresh = _live_changes(source, targets)
    assert fresh != copy
    assert np.array_equal(followed, helpers.coords(fresh))


def test_a_topology_change_makes_the_settings_changes_again_without_the_handle(addon, follow):
    source, targets = _source_with_a_handle()
    copy = _live_changes(source, targets)
    _subdivide_some_edges(source)
    assert follow.settle(60.0)
    status = follow.status(copy)
    assert "from scratch" in status and "handle moves" in status
    followed = helpers.coords(copy)
    assert len(followed) == len(source.data.vertices) and np.isfinite(followed).all()
    assert np.array_equal(followed, _replayed(copy))


def test_a_region_repainted_while_it_ran_is_made_again_bit_for_bit(addon, follow):
    source = helpers.suzanne(levels=1)
    helpers.add_slot(source, 'CUBE')
    rest = helpers.coords(source)
    helpers.add_group(source, "Paint", np.flatnonzero(rest[:, 2] > 0.0), weight=0.3)
    source.gauss_stylization.styles[0].vertex_group = "Paint"
    source.gauss_stylization.output = 'NEW_OBJECT'
    source.gauss_stylization.follow_edits = True
    live = helpers.live_run_with_a_repaint(source, "Paint", 0.9, ticks_before=5, ticks_after=8)
    live.keep()
    copy = bpy.data.objects[source.name + "_stylized"]
    kept = helpers.coords(copy)
    assert [e.get("repainted") for e in follow_store_events(addon, copy)] == [["REGIONS"]]
    source.vertex_groups["Paint"].add(list(range(len(rest))), 0.1, 'REPLACE')  # painted again since
    follow._mark([copy.name], force=True)
    assert follow.settle(60.0)
    assert np.array_equal(helpers.coords(copy), kept)


def follow_store_events(addon, copy):
    return addon.mesh.follow_store.load(copy)[1]["run"]["events"]


def test_a_saved_file_follows_again_when_opened(addon, follow, tmp_path):
    source, copy = _kept_copy(addon)
    names = source.name, copy.name
    path = str(tmp_path / "follow_edits.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    assert names[1] in follow._dirty  # re-armed by the load
    started = follow.stats["started"]
    assert follow.settle(60.0)
    assert follow.stats["started"] == started  # the source is as the kept run read it: nothing to re-run
    source, copy = (bpy.data.objects[name] for name in names)
    _edit(source)
    assert follow.settle(60.0)
    assert follow.stats["started"] == started + 1
    assert follow.panel_lines(source) == ["'%s': %s" % (copy.name, follow.status(copy))]
    assert np.array_equal(helpers.coords(copy), _replayed(copy))


@pytest.mark.parametrize("edit_mode", [False, True])
def test_while_edits_go_on_the_preview_follows_them_and_nothing_is_solved(addon, follow, monkeypatch, edit_mode):
    source, copy = _kept_copy(addon)
    _edit(source)
    assert follow.settle(60.0)
    exact, start = helpers.coords(copy), helpers.coords(source)
    monkeypatch.setattr(follow, "QUIET_SECONDS", 1e6)  # the edits never pause
    monkeypatch.setattr(follow, "PREVIEW_SECONDS", 0.0)
    started, previews = follow.stats["started"], follow.stats["previews"]
    if edit_mode:
        _edit_in_edit_mode(source, (0.04, 0.0, 0.0), count=25)
    else:
        _edit(source, (0.04, 0.0, 0.0), count=25)
    follow._tick()
    assert follow.stats["previews"] == previews + 1 and follow.stats["started"] == started
    moved = np.zeros_like(start)
    moved[:25, 0] = np.float32(0.04)
    np.testing.assert_allclose(helpers.coords(copy), exact + moved, atol=1e-6)
    if edit_mode:
        bpy.ops.object.mode_set(mode='OBJECT')
