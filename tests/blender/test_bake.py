"""Bakes to a point cache: Bake Animation (every frame of an armature animation) and Bake Progress
(one stylization recorded step by step), read back from the .pc2 and played by the Mesh Cache modifier."""

import os
import re
import subprocess

import bpy
import numpy as np
import pytest

import helpers
import rig
from blender_process import blender_command


def _bake_animation(path, first=1, last=10, warm_start=False):
    return bpy.ops.object.gauss_bake_animation(frame_start=first, frame_end=last, filepath=str(path),
                                               warm_start=warm_start)


def _stylized_alone(obj, frame, steps):
    """Stylize ``frame`` of ``obj`` on its own (Use Modifiers, New Object), as an artist would
    without a bake; the object's bake is switched off meanwhile. Returns the coordinates."""
    addon = helpers.scene_kit.addon or __import__("gauss_stylization")
    modifier = addon.mesh.cache_modifier.find(obj)
    if modifier is not None:
        modifier.show_viewport = False
    bpy.context.scene.frame_set(frame)
    helpers.activate(obj)
    assert helpers.stylize(steps, use_modifiers=True, output='NEW_OBJECT') == {'FINISHED'}
    new = bpy.context.active_object
    result = helpers.coords(new)
    bpy.data.objects.remove(new)
    if modifier is not None:
        modifier.show_viewport = True
    helpers.activate(obj)
    return result


def test_cold_bake_frames_equal_stylizing_each_frame_alone(addon, tmp_path):
    obj = rig.bent_capsule()
    rest = {frame: rig.shown_at(obj, frame) for frame in (1, 5, 10)}
    path = tmp_path / "capsule.pc2"
    assert _bake_animation(path) == {'FINISHED'}
    cache = addon.pc2.read(str(path))
    assert cache.frames.shape == (10, len(obj.data.vertices), 3) and (cache.start, cache.rate) == (1.0, 1.0)
    steps = obj.gauss_stylization.bake_steps
    for frame in (1, 5, 10):
        assert np.array_equal(cache.frames[frame - 1], _stylized_alone(obj, frame, steps)), frame
        assert np.abs(cache.frames[frame - 1] - rest[frame]).max() > 1e-2  # it is stylized
    # The rig moves the mesh: the frames differ.
    assert np.abs(cache.frames[9] - cache.frames[0]).max() > 0.5


def _animation_at(addon, obj, frame):
    """The animated (armature-deformed) mesh at ``frame``, the object's bake switched off."""
    modifier = addon.mesh.cache_modifier.find(obj)
    if modifier is not None:
        modifier.show_viewport = False
    shown = rig.shown_at(obj, frame)
    if modifier is not None:
        modifier.show_viewport = True
    return shown


def _offsets(frames, rests):
    """Mean distance of each frame's result from its own rest shape: how stylized it is."""
    return np.array([np.linalg.norm(y - r, axis=1).mean() for y, r in zip(frames, rests)])


def test_warm_bake_continues_each_frame_from_the_previous_result(addon, tmp_path):
    # What bake.py defines: frame 1 = Script Steps from its rest shape (Stylize on frame 1 alone);
    # frame f > 1 starts at X_f = Y_{f-1} + (R_f - R_{f-1}) and runs Bake Steps. Replayed here with
    # gauss_core directly (the default style and settings, which the bake's default slot has).
    obj = rig.bent_capsule()
    settings = obj.gauss_stylization
    warm, cold = tmp_path / "warm.pc2", tmp_path / "cold.pc2"
    assert _bake_animation(warm, 1, 10, warm_start=True) == {'FINISHED'}
    frames = addon.pc2.read(str(warm)).frames
    assert np.array_equal(frames[0], _stylized_alone(obj, 1, settings.iterations))
    core, triangles = addon.native.core(), helpers.triangles(obj)[0]
    rests = [_animation_at(addon, obj, frame) for frame in range(1, 11)]
    result = None
    for frame in range(1, 6):
        rest = rests[frame - 1]
        solver = core.Solver(rest, triangles, lam=settings.lam, admm_iterations=settings.admm_iterations,
                             resolution_independent=settings.resolution_independent)
        if result is None:
            solver.step(settings.iterations)
        else:
            solver.set_vertices(result + (rest - rests[frame - 2]))
            solver.step(settings.bake_steps)
        result = np.empty_like(rest)
        solver.vertices_into(result)
    assert np.array_equal(frames[4], result)
    # The style carries over: every warm frame is about as stylized as the first, while cold frames
    # (Bake Steps from their rest shape each) are much less, Bake Steps being fewer than Script Steps.
    assert _bake_animation(cold, 1, 10, warm_start=False) == {'FINISHED'}
    warm_offsets = _offsets(frames, rests)
    cold_offsets = _offsets(addon.pc2.read(str(cold)).frames, rests)
    print("mean offset from the rest shape, warm:", np.round(warm_offsets, 4), "cold:", np.round(cold_offsets, 4))
    assert np.all(warm_offsets[1:] > 0.8 * warm_offsets[0])
    assert np.all(cold_offsets[1:] < warm_offsets[1:]) and cold_offsets[1:].mean() < 0.6 * warm_offsets[1:].mean()


def test_warm_bake_with_script_steps_0_starts_from_a_converged_first_frame(addon, tmp_path):
    obj = rig.bent_capsule()
    obj.gauss_stylization.iterations = 0  # until converged, as Stylize runs it
    path = tmp_path / "warm.pc2"
    assert _bake_animation(path, 1, 3, warm_start=True) == {'FINISHED'}
    assert np.array_equal(addon.pc2.read(str(path)).frames[0], _stylized_alone(obj, 1, 0))


def test_playback_shows_the_baked_frames_exactly(addon, tmp_path):
    obj = rig.bent_capsule()
    path = tmp_path / "capsule.pc2"
    assert _bake_animation(path) == {'FINISHED'}
    modifier = obj.modifiers[-1]
    assert modifier.name == addon.mesh.cache_modifier.NAME and modifier.type == 'MESH_CACHE'
    assert (modifier.cache_format, modifier.filepath, modifier.frame_start) == ('PC2', str(path), 1.0)
    assert [m.type for m in obj.modifiers] == ['ARMATURE', 'MESH_CACHE']
    cache = addon.pc2.read(str(path))
    for frame in range(1, 11):
        assert np.array_equal(rig.shown_at(obj, frame), cache.frames[frame - 1]), frame
    # Baking again updates the one modifier, and reads the animation, not the previous bake.
    assert _bake_animation(path, 3, 6) == {'FINISHED'}
    assert [m.type for m in obj.modifiers] == ['ARMATURE', 'MESH_CACHE'] and obj.modifiers[-1].frame_start == 3
    assert np.array_equal(addon.pc2.read(str(path)).frames, cache.frames[2:6])


def test_cold_frames_are_the_same_whichever_range_they_were_baked_in(addon, tmp_path):
    obj = rig.bent_capsule()
    whole, part = tmp_path / "whole.pc2", tmp_path / "part.pc2"
    assert _bake_animation(whole, 1, 10) == {'FINISHED'}
    assert _bake_animation(part, 4, 7) == {'FINISHED'}
    cache = addon.pc2.read(str(part))
    assert cache.start == 4.0
    assert np.array_equal(cache.frames, addon.pc2.read(str(whole)).frames[3:7])


def test_bake_progress_frame_k_is_k_steps_of_a_scripted_run(addon, tmp_path):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    path = tmp_path / "progress.pc2"
    assert bpy.ops.object.gauss_bake_progress(steps=12, steps_per_frame=3, frame_start=5,
                                              filepath=str(path)) == {'FINISHED'}
    cache = addon.pc2.read(str(path))
    assert cache.frames.shape[0] == 5 and cache.start == 5.0
    assert np.array_equal(helpers.coords(obj), start)  # the mesh itself is not changed
    for k in range(5):
        if k:  # (a scripted run of 0 steps runs until converged; frame 0 is the mesh before any step)
            helpers.stylize(3 * k)
        assert np.array_equal(cache.frames[k], helpers.coords(obj)), k
        bpy.context.scene.frame_set(5 + k)
        helpers.mesh_io.write_vertex_coords(obj.data, start)  # back to the start: the next run is fresh
        obj.data.update()
        assert np.array_equal(helpers.evaluated_coords(obj), cache.frames[k])  # played back
    assert obj.modifiers[0].name == addon.mesh.cache_modifier.NAME  # base-mesh bake: first in the stack


def test_bake_progress_of_the_evaluated_mesh_goes_last(addon, tmp_path):
    obj = helpers.suzanne(levels=0)
    obj.modifiers.new("Subdivision", 'SUBSURF').levels = 1
    obj.gauss_stylization.use_modifiers = True
    path = tmp_path / "progress.pc2"
    assert bpy.ops.object.gauss_bake_progress(steps=4, steps_per_frame=2, filepath=str(path)) == {'FINISHED'}
    cache = addon.pc2.read(str(path))
    assert cache.frames.shape == (3, len(helpers.evaluated_coords(obj)), 3)
    assert [m.type for m in obj.modifiers] == ['SUBSURF', 'MESH_CACHE']
    bpy.context.scene.frame_set(3)
    assert np.array_equal(helpers.evaluated_coords(obj), cache.frames[2])


def _folder_listing(path):
    return sorted(os.listdir(path))


def test_a_cancelled_bake_leaves_no_file_no_modifier_and_the_frame(addon, tmp_path):
    obj = rig.bent_capsule()
    helpers.settings_io.add_slot(obj.gauss_stylization, {"preset": 'CUBE'})
    bpy.context.scene.frame_set(7)
    path = tmp_path / "capsule.pc2"
    job = addon.bake.bake.AnimationBake(bpy.context, obj, 1, 10, str(path), warm_start=False)
    job.advance()
    job.advance()
    assert len(_folder_listing(tmp_path)) == 1  # the temporary file
    job.cancel()
    assert _folder_listing(tmp_path) == [] and addon.mesh.cache_modifier.find(obj) is None
    assert bpy.context.scene.frame_current == 7


def test_a_cancelled_bake_keeps_the_previous_bake(addon, tmp_path):
    obj = rig.bent_capsule()
    path = tmp_path / "capsule.pc2"
    assert _bake_animation(path) == {'FINISHED'}
    before = path.read_bytes()
    job = addon.bake.bake.AnimationBake(bpy.context, obj, 2, 4, str(path), warm_start=False)
    assert not addon.mesh.cache_modifier.find(obj).show_viewport  # off while the bake reads the animation
    job.advance()
    job.cancel()
    assert path.read_bytes() == before and _folder_listing(tmp_path) == ["capsule.pc2"]
    modifier = addon.mesh.cache_modifier.find(obj)
    assert modifier.show_viewport and modifier.frame_start == 1


def test_a_failed_bake_leaves_nothing(addon, tmp_path):
    # Vertices that change over the frames cannot go into a point cache.
    obj = rig.bent_capsule()
    subdivision = obj.modifiers.new("Subdivision", 'SUBSURF')
    subdivision.levels = 0
    subdivision.keyframe_insert("levels", frame=3)
    subdivision.levels = 1
    subdivision.keyframe_insert("levels", frame=4)
    with pytest.raises(RuntimeError, match="at frame 4"):
        _bake_animation(tmp_path / "capsule.pc2")
    assert _folder_listing(tmp_path) == [] and addon.mesh.cache_modifier.find(obj) is None
    assert bpy.context.scene.frame_current == 1


@pytest.mark.parametrize("call, message", [
    (lambda path: bpy.ops.object.gauss_bake_animation(frame_start=5, frame_end=2, filepath=path), "before the first"),
    (lambda path: bpy.ops.object.gauss_bake_progress(steps=10, steps_per_frame=3, filepath=path), "multiple"),
    (lambda path: bpy.ops.object.gauss_bake_animation(filepath=os.path.dirname(path)), "is a folder"),
    (lambda path: bpy.ops.object.gauss_bake_animation(filepath="/proc/no/x.pc2"), "cannot make the folder"),
    (lambda path: bpy.ops.object.gauss_bake_animation(filepath="//x.pc2"), "Save the .blend file first"),
])
def test_bad_bake_requests_are_refused_with_a_message(addon, tmp_path, call, message):
    obj = rig.bent_capsule()
    with pytest.raises(RuntimeError, match=message):
        call(str(tmp_path / "x.pc2"))
    assert _folder_listing(tmp_path) == [] and addon.mesh.cache_modifier.find(obj) is None
    assert len(obj.gauss_stylization.styles) == 0  # a failed start changes no setting


_HEADLESS = """
import sys, bpy
sys.path.insert(0, sys.argv[-1])
import gauss_stylization
gauss_stylization.register()
bpy.ops.object.gauss_bake_animation(frame_start=1, frame_end=40, warm_start=False)
bpy.ops.wm.save_mainfile()
"""


def test_headless_bake_prints_progress_and_keeps_a_relative_path(addon, tmp_path):
    obj = rig.bent_capsule(frames=(1, 40))
    obj.gauss_stylization.bake_steps = 300  # long enough (seconds) for progress.ProgressReport to show it
    blend = tmp_path / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    result = subprocess.run(blender_command(_HEADLESS, [helpers.ADDON_DIR], blend=str(blend)),
                            capture_output=True, text=True, timeout=300)
    out = result.stdout + result.stderr
    assert result.returncode == 0, out
    lines = re.findall(r"Gauss Bake Animation 'Capsule': frame (\d+) of 40\.\.\. (\d+)%", out)
    tenths = [int(percent) // 10 for _frame, percent in lines]
    # Shown after half a second (progress.SHOW_AFTER), then a line for every tenth passed, up to the end.
    assert tenths and tenths[0] <= 5 and tenths == list(range(tenths[0], 11)), out
    assert "Gauss Bake Animation 'Capsule': done in" in out
    assert (tmp_path / "Capsule_gauss.pc2").is_file()
    bpy.ops.wm.open_mainfile(filepath=str(blend))
    modifier = bpy.data.objects["Capsule"].modifiers[-1]
    assert modifier.type == 'MESH_CACHE' and modifier.filepath == "//Capsule_gauss.pc2"


class _Recorder:
    """A stand-in for a panel's layout that records what is drawn."""

    def __init__(self, rows):
        self.rows = rows

    def prop(self, _owner, name, **_options):
        self.rows.append(name)

    def operator(self, idname, **_options):
        self.rows.append(idname)

    def label(self, text="", **_options):
        self.rows.append("label: " + text)

    def column(self, **_options):
        return self

    row = column


def _bake_panel_rows(addon):
    rows = []
    addon.bake.bake_ui.VIEW3D_PT_gauss_bake.draw(type("Panel", (), {"layout": _Recorder(rows)})(), bpy.context)
    return rows


def _shows(rows, text):
    """Do the panel's labels show ``text``? A label wraps to the sidebar's width over several rows,
    between words and inside a long path, so the texts are compared without their spaces."""
    said = "".join(row[len("label: "):] for row in rows if row.startswith("label: "))
    return "".join(text.split()) in "".join(said.split())


def test_the_bake_panel_offers_its_settings_and_both_bakes(addon, tmp_path):
    obj = rig.bent_capsule()
    rows = _bake_panel_rows(addon)
    assert [row for row in rows if not row.startswith("label")] == [
        "bake_steps", "bake_warm_start", "bake_warmup_frames", "bake_scene_range", "bake_filepath",
        "object.gauss_bake_animation", "object.gauss_bake_progress"]
    assert _shows(rows, "Frames 1 to 10 (the scene's)")
    obj.gauss_stylization.bake_warm_start = False  # Warm-up only matters with Warm Start
    assert "bake_warmup_frames" not in _bake_panel_rows(addon)
    obj.gauss_stylization.bake_warm_start = True
    obj.gauss_stylization.bake_scene_range = False
    assert ["bake_frame_start", "bake_frame_end"] == [row for row in _bake_panel_rows(addon) if row.startswith("bake_frame")]
    assert _bake_animation(tmp_path / "c.pc2") == {'FINISHED'}
    assert _shows(_bake_panel_rows(addon), "Gauss Bake plays %s" % (tmp_path / "c.pc2"))
    assert obj.modifiers[-1].type == 'MESH_CACHE'


def test_the_bake_panel_settings_are_what_bake_animation_uses(addon, tmp_path):
    obj = rig.bent_capsule(frames=(1, 40))
    settings = obj.gauss_stylization
    settings.bake_scene_range = False
    settings.bake_frame_start, settings.bake_frame_end = 3, 6
    settings.bake_filepath = str(tmp_path / "from_panel.pc2")
    settings.bake_steps = 2
    assert bpy.ops.object.gauss_bake_animation() == {'FINISHED'}
    cache = addon.pc2.read(str(tmp_path / "from_panel.pc2"))
    assert cache.frames.shape[0] == 4 and cache.start == 3


def test_an_unsaved_file_bakes_to_the_temporary_folder(addon, tmp_path, monkeypatch):
    monkeypatch.setattr(addon.bake.bake, "blend_saved", lambda: False)  # other tests saved this session's file
    filepaths = bpy.context.preferences.filepaths
    previous = filepaths.temporary_directory
    filepaths.temporary_directory = str(tmp_path)
    try:
        obj = rig.bent_capsule(frames=(1, 3))
        bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, 3
        assert _shows(_bake_panel_rows(addon), "Writes %s" % (tmp_path / "Capsule_gauss.pc2"))
        assert bpy.ops.object.gauss_bake_animation() == {'FINISHED'}
        assert addon.mesh.cache_modifier.find(obj).filepath == str(tmp_path / "Capsule_gauss.pc2")
        assert "Capsule_gauss.pc2" in _folder_listing(tmp_path)  # (beside the session folder Blender made there)
    finally:
        filepaths.temporary_directory = previous


def test_a_cache_modifier_saved_under_the_old_name_is_found_and_renamed(addon, tmp_path):
    obj = rig.bent_capsule()
    old = obj.modifiers.new(addon.mesh.cache_modifier.OLD_NAMES[0], 'MESH_CACHE')
    assert addon.mesh.cache_modifier.find(obj) == old
    assert _bake_animation(tmp_path / "c.pc2") == {'FINISHED'}
    caches = [m for m in obj.modifiers if m.type == 'MESH_CACHE']
    assert len(caches) == 1 and caches[0].name == addon.mesh.cache_modifier.NAME == "Gauss Bake"


def test_the_object_deleted_mid_bake_ends_it_leaving_nothing(addon, tmp_path):
    obj = rig.bent_capsule()
    helpers.settings_io.add_slot(obj.gauss_stylization, {"preset": 'CUBE'})
    job = addon.bake.bake.AnimationBake(bpy.context, obj, 1, 10, str(tmp_path / "c.pc2"), warm_start=False)
    job.advance()
    bpy.data.objects.remove(obj)
    with pytest.raises(ReferenceError):
        job.advance()
    job.cancel()
    assert _folder_listing(tmp_path) == [] and bpy.context.scene.frame_current == 1
