"""A file saved during a live run holds the meshes as they were before it (what Esc restores), for
every Output, while the run goes on with its result; a save that fails puts the result back at the
next tick. The windowed test (windowed_undo_save.py) presses Ctrl+S in a real window and reopens."""

import os

import bpy
import numpy as np
import pytest

import helpers


class _Run:
    """Stands for the modal operator as runs.py sees it around a save."""

    def __init__(self, live):
        self.live, self.reports = live, []

    def hold_for_save(self, context):
        self.live.hold_for_save()

    def resume_after_save(self, context):
        self.live.resume_after_save()


@pytest.fixture
def running(addon):
    """Registers a _Run of a live run of ``obj`` (as Stylize does) and ends it afterwards."""
    runs = []

    def start(obj):
        live = helpers.live_run([obj])
        run = _Run(live)
        addon.run.runs.start([obj], run)
        runs.append(run)
        return live

    yield start
    for run in runs:
        run.live.cancel()
        addon.run.runs.forget(run)


def _saved(tmp_path, name):
    """Save a copy of the file; read back the mesh ``name`` from it (None if it is not there)
    and the names of its objects."""
    path = os.path.join(str(tmp_path), "mid_run.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, copy=True)
    with bpy.data.libraries.load(path) as (source, loaded):
        objects = list(source.objects)
        loaded.meshes = [name] if name in source.meshes else []
    mesh = loaded.meshes[0] if loaded.meshes else None
    if mesh is None:
        return None, None, objects
    out = np.empty((len(mesh.vertices), 3), np.float32)
    mesh.vertices.foreach_get("co", out.reshape(-1))
    keys = None if mesh.shape_keys is None else [k.name for k in mesh.shape_keys.key_blocks]
    bpy.data.meshes.remove(mesh)
    return out, keys, objects


def _step(live, count=5):
    for _ in range(count):
        live.tick()


@pytest.mark.parametrize("output", ['MESH', 'SHAPE_KEY'])
def test_a_save_mid_run_holds_the_mesh_as_before_the_run_and_the_run_goes_on(addon, running, tmp_path, output):
    obj = helpers.suzanne(levels=1)
    obj.gauss_stylization.output = output
    start = helpers.coords(obj)
    live = running(obj)
    _step(live)
    session = live.sessions[0]
    shown = helpers.coords(obj) if output == 'MESH' else helpers.key_coords(
        obj.data.shape_keys.key_blocks["Gauss Stylized"])
    assert not np.array_equal(shown, start)
    saved, keys, _objects = _saved(tmp_path, obj.data.name)
    assert np.array_equal(saved, start) and keys is None  # no shape key the run made
    # The run goes on from where it was, with its result shown again.
    now = helpers.coords(obj) if output == 'MESH' else helpers.key_coords(
        obj.data.shape_keys.key_blocks["Gauss Stylized"])
    assert np.array_equal(now, shown) and not live.held
    steps = session.steps
    _step(live, 1)
    assert session.steps == steps + 1


def test_a_save_mid_run_leaves_out_the_new_object(addon, running, tmp_path):
    obj = helpers.suzanne(levels=1)
    obj.gauss_stylization.output = 'NEW_OBJECT'
    live = running(obj)
    _step(live)
    new_name = obj.name + addon.settings.schema.NEW_OBJECT_SUFFIX
    assert new_name in bpy.data.objects and obj.display_type == 'WIRE'
    display = obj.display_type
    _saved_coords, _keys, objects = _saved(tmp_path, obj.data.name)
    assert new_name not in objects and obj.name in objects
    assert new_name in bpy.data.objects and bpy.data.objects[new_name].users_collection  # back in the scene
    assert obj.display_type == display


def test_a_save_that_never_finished_gets_the_result_back_at_the_next_tick(addon, running):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    live = running(obj)
    _step(live)
    live.hold_for_save()  # as save_pre does; a failed write never calls save_post
    assert np.array_equal(helpers.coords(obj), start)
    live.tick()
    assert not live.held and not np.array_equal(helpers.coords(obj), start)
