"""The farm's command line (bake/farm_cli.py, docs/baking.md "On a render farm"): chunks of an animation
bake merged into the cache of one bake, warm-up frames with Warm Start, a line per frame, the settings
from the .blend, the script run from where the add-on is installed, errors; a batch of files stylized
with a saved preset. The engines that run it (Slurm, Open Job Description, Flamenco) are tests/farm."""

import json
import os
import re
import shutil
import subprocess

import bpy
import numpy as np
import pytest

import helpers
import rig
from blender_process import blender_command

# Warm Start chunks: largest vertex distance from the one-process bake, over the capsule's size, that a
# chunk with the default Warm-up may show on this shot (docs/baking.md, "Warm Start in chunks").
WARM_TOLERANCE = 0.02


def _cli(addon, *args):
    return addon.bake.farm_cli.main([str(a) for a in args])


def _shot(warm_start, frames=(1, 12)):
    obj = rig.bent_capsule(frames=frames)  # the scene's range is the shot's
    helpers.settings_io.apply_dict(obj.gauss_stylization, {
        "lam": 2.0, "iterations": 20, "bake_steps": 4, "bake_warm_start": warm_start, "bake_scene_range": True,
        "styles": [{"preset": 'CUBE'}]})
    return obj


def _one_bake(path):
    assert bpy.ops.object.gauss_bake_animation(filepath=str(path)) == {'FINISHED'}
    return path


def _frame_lines(text):
    return [(int(f), int(n), int(t)) for f, n, t in re.findall(r"gauss_bake: frame (-?\d+): (\d+)/(\d+) \(", text)]


def test_chunks_without_warm_start_merge_into_the_bytes_of_one_bake(addon, tmp_path, capsys):
    _shot(warm_start=False)
    one = _one_bake(tmp_path / "one.pc2")
    for first, last in ((1, 5), (6, 9), (10, 12)):
        assert _cli(addon, "bake", "--object", "Capsule", "--frames", "%d-%d" % (first, last),
                    "--out", tmp_path / ("chunk_%d.pc2" % first)) == 0
    out = capsys.readouterr().out
    # A line per frame as it is baked (a farm's task timeout sees the job alive).
    assert _frame_lines(out) == ([(f, f, 5) for f in range(1, 6)] + [(f, f - 5, 4) for f in range(6, 10)]
                                 + [(f, f - 9, 3) for f in range(10, 13)])
    assert "warm-up" not in out
    # A glob the shell did not expand is expanded (chunk_10 sorts before chunk_6: the frames decide).
    assert _cli(addon, "merge", tmp_path / "chunk_*.pc2", "--frames", "1-12", "--out", tmp_path / "merged.pc2") == 0
    assert (tmp_path / "merged.pc2").read_bytes() == one.read_bytes()


def test_frames_as_flamenco_and_blender_write_them(addon, tmp_path):
    """Flamenco's frameChunker writes a chunk of two frames as 'A,B' and Blender's own ranges are 'A..B':
    a chunk given either way bakes its frames, and the merge takes them too."""
    _shot(warm_start=False, frames=(1, 6))
    one = _one_bake(tmp_path / "one.pc2")
    for name, frames in (("a", "1..3"), ("b", "4,5"), ("c", "6")):
        assert _cli(addon, "bake", "--object", "Capsule", "--frames", frames, "--out", tmp_path / (name + ".pc2")) == 0
    assert _cli(addon, "merge", tmp_path / "?.pc2", "--frames", "1..6", "--out", tmp_path / "merged.pc2") == 0
    assert (tmp_path / "merged.pc2").read_bytes() == one.read_bytes()


def _relative_error(addon, chunk, one, first, size):
    frames = addon.pc2.read(str(chunk)).frames
    return np.abs(frames - addon.pc2.read(str(one)).frames[first - 1:first - 1 + len(frames)]).max() / size


def test_warm_start_chunks_warm_up_before_their_first_frame(addon, tmp_path, capsys):
    obj = _shot(warm_start=True, frames=(1, 24))
    settings = obj.gauss_stylization
    size = float(np.ptp(helpers.coords(obj), axis=0).max())
    one = _one_bake(tmp_path / "one.pc2")
    # A chunk from the shot's first frame has nothing to warm up from: the frames of the one bake.
    assert _cli(addon, "bake", "--object", "Capsule", "--frames", "1-8", "--out", tmp_path / "a.pc2") == 0
    assert np.array_equal(addon.pc2.read(str(tmp_path / "a.pc2")).frames, addon.pc2.read(str(one)).frames[:8])
    capsys.readouterr()
    errors = {}
    for warmup in (0, 2, settings.bake_warmup_frames):
        settings.bake_warmup_frames = warmup
        chunk = tmp_path / ("b%d.pc2" % warmup)
        assert _cli(addon, "bake", "--object", "Capsule", "--frames", "17-24", "--out", chunk) == 0
        out = capsys.readouterr().out
        assert re.findall(r"frame (\d+): warm-up (\d+)/(\d+)", out) == [
            (str(17 - warmup + k), str(k + 1), str(warmup)) for k in range(warmup)]
        assert [line[0] for line in _frame_lines(out)] == list(range(17, 25))
        assert addon.pc2.read(str(chunk)).start == 17.0
        errors[warmup] = _relative_error(addon, chunk, one, 17, size)
    print("largest distance from the one bake / size, by warm-up frames:", errors)
    assert errors[0] > errors[2] > errors[8]
    assert errors[8] < WARM_TOLERANCE
    # The shot in three chunks with the default Warm-up, merged: within the tolerance of the one bake.
    assert _cli(addon, "bake", "--object", "Capsule", "--frames", "9-16", "--out", tmp_path / "c.pc2") == 0
    merged = tmp_path / "merged.pc2"
    assert _cli(addon, "merge", tmp_path / "a.pc2", tmp_path / "c.pc2", tmp_path / "b8.pc2", "--frames", "1-24",
                "--out", merged) == 0
    assert _relative_error(addon, merged, one, 1, size) < WARM_TOLERANCE


def _farm_cli_script():
    return os.path.join(helpers.ADDON_DIR, "gauss_stylization", "bake", "farm_cli.py")


def _run_script(farm_cli, args, blend=None, env=None):
    """farm_cli.py run as a script: `blender -b FILE -P farm_cli.py -- ARGS` in Blender, the same through
    runpy in Blender as a Python module."""
    if bpy.app.binary_path:
        argv = ([bpy.app.binary_path, "-b"] + ([str(blend)] if blend else [])
                + ["--factory-startup", "--python-exit-code", "1", "-P", farm_cli, "--"] + [str(a) for a in args])
    else:
        script = ("import runpy\ntry:\n    runpy.run_path(%r, run_name='__main__')\n"
                  "except SystemExit as exc:\n    if exc.code:\n        raise\n" % farm_cli)
        argv = blender_command(script, [str(a) for a in args], blend=str(blend) if blend else None)
    return subprocess.run(argv, capture_output=True, text=True, timeout=300, env=env, stdin=subprocess.DEVNULL)


def test_the_script_bakes_with_the_settings_saved_in_the_blend_file(addon, tmp_path):
    obj = _shot(warm_start=False, frames=(1, 6))
    obj.gauss_stylization.lam = 3.5  # not the default: the worker must read it from the file
    blend = tmp_path / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    one = _one_bake(tmp_path / "one.pc2")
    result = _run_script(_farm_cli_script(), ["bake", "--object", "Capsule", "--frames", "1-6",
                                              "--out", tmp_path / "chunk.pc2"], blend=blend)
    assert result.returncode == 0, result.stdout + result.stderr
    assert _frame_lines(result.stdout) == [(f, f, 6) for f in range(1, 7)]
    assert (tmp_path / "chunk.pc2").read_bytes() == one.read_bytes()


@pytest.mark.skipif(not bpy.app.binary_path, reason="Blender as a module: the suite itself runs on the "
                    "installed extension, so the test above runs the script from its install")
def test_the_script_runs_from_a_classic_add_on_install(addon, tmp_path):
    _shot(warm_start=False, frames=(1, 3))
    blend = tmp_path / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    installed = tmp_path / "scripts" / "addons" / "gauss_stylization"
    shutil.copytree(os.path.join(helpers.ADDON_DIR, "gauss_stylization"), installed,
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, BLENDER_USER_SCRIPTS=str(tmp_path / "scripts"))
    result = _run_script(str(installed / "bake" / "farm_cli.py"),
                         ["bake", "--object", "Capsule", "--frames", "1-3", "--out", tmp_path / "c.pc2"], blend, env)
    assert result.returncode == 0, result.stdout + result.stderr
    # Found among Blender's add-ons by its folder and enabled by its name (not imported from the folder).
    assert "gauss_bake: add-on 'gauss_stylization' enabled from %s" % installed in result.stdout, result.stdout
    assert addon.pc2.read(str(tmp_path / "c.pc2")).frames.shape[0] == 3


_MANIFEST = """schema_version = "1.0.0"
id = "gauss_stylization"
version = "0.1.0"
name = "Gauss Stylization"
tagline = "Stylize meshes by the face normals they should prefer"
maintainer = "tests"
type = "add-on"
blender_version_min = "4.2.0"
license = ["SPDX:GPL-3.0-or-later"]
"""


@pytest.mark.skipif(bpy.app.version < (4, 2, 0), reason="Blender %s has no extensions (4.2 and later)"
                    % bpy.app.version_string)
def test_the_script_runs_from_an_extension_install(addon, tmp_path):
    _shot(warm_start=False, frames=(1, 3))
    blend = tmp_path / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    if os.path.basename(helpers.ADDON_DIR) == "user_default":  # the suite runs on an installed extension
        installed, env = os.path.join(helpers.ADDON_DIR, "gauss_stylization"), None
    else:  # the build's add-on (the solver inside it) as an extension of a throw-away user folder
        user = tmp_path / "user"
        installed = str(user / "extensions" / "user_default" / "gauss_stylization")
        shutil.copytree(os.path.join(helpers.ADDON_DIR, "gauss_stylization"), installed,
                        ignore=shutil.ignore_patterns("__pycache__"))
        with open(os.path.join(installed, "blender_manifest.toml"), "w") as handle:
            handle.write(_MANIFEST)
        env = dict(os.environ, BLENDER_USER_RESOURCES=str(user), BLENDER_USER_CONFIG=str(user / "config"),
                   BLENDER_USER_SCRIPTS=str(user / "scripts"), BLENDER_USER_DATAFILES=str(user / "datafiles"))
    result = _run_script(os.path.join(installed, "bake", "farm_cli.py"),
                         ["bake", "--object", "Capsule", "--frames", "1-3", "--out", tmp_path / "c.pc2"], blend, env)
    assert result.returncode == 0, result.stdout + result.stderr
    # The package Blender knows: bl_ext.<repository>.<name>, not a second copy imported from the folder.
    assert re.search(r"gauss_bake: add-on 'bl_ext\.user_default\.gauss_stylization' (loaded|enabled) from %s"
                     % re.escape(os.path.realpath(installed)), result.stdout), result.stdout
    assert addon.pc2.read(str(tmp_path / "c.pc2")).frames.shape[0] == 3


def test_the_command_form_opens_the_blend_file_it_is_given(addon, tmp_path, capsys):
    """`blender --command gauss_bake` opens no file before calling main(): its --blend option does, before or
    after the job's name, and a file that is not there or not a .blend is an error, not a traceback."""
    _shot(warm_start=False, frames=(1, 3))
    blend = tmp_path / "shot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    one = _one_bake(tmp_path / "one.pc2")
    junk = tmp_path / "junk.blend"
    junk.write_bytes(b"BLENDER-v300 but nothing else")
    bpy.ops.wm.read_homefile(use_empty=True)  # as a command starts: not the shot
    job = ["--object", "Capsule", "--frames", "1-3", "--out"]
    assert _cli(addon, "bake", "--blend", blend, *job, tmp_path / "a.pc2") == 0
    assert _cli(addon, "--blend", blend, "bake", *job, tmp_path / "b.pc2") == 0
    assert (tmp_path / "a.pc2").read_bytes() == (tmp_path / "b.pc2").read_bytes() == one.read_bytes()
    capsys.readouterr()
    for path, message in ((tmp_path / "none.blend", "No .blend file"), (junk, "junk.blend")):
        assert _cli(addon, "bake", "--blend", path, "--object", "Capsule", "--frames", "1-3",
                    "--out", tmp_path / "c.pc2") == 1
        err = capsys.readouterr().err
        assert message in err and "Traceback" not in err, err
    assert not (tmp_path / "c.pc2").exists()


@pytest.mark.parametrize("args, message", [
    (["bake", "--object", "Nobody", "--frames", "1-3"], "No object 'Nobody'"),
    (["bake", "--object", "Rig", "--frames", "1-3"], "'Rig' is not a mesh object (its type is ARMATURE)"),
    (["bake", "--object", "Capsule", "--frames", "1to3"], "Frames must be A-B"),
    (["bake", "--object", "Capsule", "--frames", "5-1"], "The last frame (1) is before the first (5)"),
    (["bake", "--object", "Capsule", "--frames", "1-3,7-9"], "Frames 1-3,7-9 are not one range"),
    (["bake", "--object", "Capsule", "--frames", "1,,2"], "Frames must be A-B"),
    # Blender would clamp the scene to its last frame and bake that one frame over and over.
    (["bake", "--object", "Capsule", "--frames", "2000000-2000001"], "Blender's frames are -1048574 to 1048574"),
    (["bake", "--object", "Capsule", "--frames", "99999999999999"], "Blender's frames are -1048574 to 1048574"),
    (["merge", "."], "'.' is a folder, not a .pc2 chunk"),
    (["merge", "part_1.pc2", "--out", "."], "The output '.' is a folder; give a file name"),
    (["merge", "missing_*.pc2"], "No file matches"),
    (["merge", "part_1.pc2", "part_7.pc2"], "a gap"),
    (["merge", "part_1.pc2", "--frames", "1-9"], "The chunks hold frames 1-3, not 1-9"),
])
def test_bad_requests_fail_with_a_message_and_write_nothing(addon, tmp_path, capsys, monkeypatch, args, message):
    _shot(warm_start=False, frames=(1, 9))
    monkeypatch.chdir(tmp_path)
    for first in (1, 7):
        assert _cli(addon, "bake", "--object", "Capsule", "--frames", "%d-%d" % (first, first + 2),
                    "--out", "part_%d.pc2" % first) == 0
    before = sorted(os.listdir(tmp_path))
    capsys.readouterr()
    assert _cli(addon, *(args + ([] if "--out" in args else ["--out", "out.pc2"]))) == 1
    assert message in capsys.readouterr().err
    assert sorted(os.listdir(tmp_path)) == before


def test_bad_arguments_print_the_usage(addon, capsys):
    assert _cli(addon, "bake", "--frames", "1-3") == 1
    assert "the following arguments are required: --object" in capsys.readouterr().err
    assert _cli(addon, "--help") == 0
    assert "bake" in capsys.readouterr().out


@pytest.mark.skipif(not hasattr(bpy.utils, "register_cli_command"), reason="Blender %s has no command line "
                    "commands (4.2 and later)" % bpy.app.version_string)
def test_the_command_is_registered_with_the_add_on(addon):
    assert len(addon.bake.farm_cli._handles) == 1


# -- a batch of files --------------------------------------------------------------------

def _write_preset(path, **settings):
    path.write_text(json.dumps(dict({"lam": 2.0, "iterations": 10, "styles": [{"preset": 'CUBE'}]}, **settings)))
    return path


def _obj_vertices(path):
    return np.array([[float(x) for x in line.split()[1:4]] for line in open(path) if line.startswith("v ")])


def test_a_batch_stylizes_each_file_and_skips_the_bad_ones(addon, tmp_path, capsys):
    rest = helpers.coords(_shot(warm_start=False, frames=(1, 3)))
    blend = tmp_path / "capsule.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    meshes = [os.path.join(helpers.MESHES, relative) for relative in
              ("bunny/bunny_npm_1839.obj", "boundary/cat_head_131.obj", "small/spot_triangulated_2930.obj")]
    junk = tmp_path / "junk.obj"
    junk.write_text("this is no mesh\n")
    notes = tmp_path / "notes.txt"
    notes.write_text("not a mesh either\n")
    broken = tmp_path / "broken.blend"  # Blender cannot read it: the next file must still open
    broken.write_bytes(b"BLENDER-v300" + bytes(range(256)) * 8)
    inputs = [meshes[0], junk, broken, blend, tmp_path / "missing.obj", notes, meshes[1], meshes[2]]
    preset = _write_preset(tmp_path / "preset.json")
    out_dir = tmp_path / "out"
    assert _cli(addon, "batch", *inputs, "--preset", preset, "--out-dir", out_dir) == 3  # some skipped
    out = capsys.readouterr().out
    skipped = re.findall(r"gauss_bake: file (\d)/8: SKIPPED (\S+): (.+)", out)
    assert [(n, os.path.basename(p)) for n, p, _reason in skipped] == [
        ("2", "junk.obj"), ("3", "broken.blend"), ("5", "missing.obj"), ("6", "notes.txt")], out
    reasons = [reason for *_, reason in skipped]
    assert reasons[:1] + reasons[2:] == ["no faces in it", "no such file", "not a .obj or .blend file"]
    assert "broken.blend" in reasons[1] and "Traceback" not in out, reasons[1]  # Blender's own words
    assert "gauss_bake: batch: 4 stylized, 4 skipped" in out
    assert sorted(os.listdir(out_dir)) == ["bunny_npm_1839_gauss.obj", "capsule_gauss.blend",
                                           "cat_head_131_gauss.obj", "spot_triangulated_2930_gauss.obj"]
    for mesh in meshes:  # one output per input: the same vertices, moved by the stylization
        before = _obj_vertices(mesh)
        after = _obj_vertices(out_dir / (os.path.basename(mesh)[:-4] + "_gauss.obj"))
        assert after.shape == before.shape and np.all(np.isfinite(after))
        assert np.abs(after - before).max() > 1e-3 * np.ptp(before, axis=0).max(), mesh
    bpy.ops.wm.open_mainfile(filepath=str(out_dir / "capsule_gauss.blend"))
    capsule = bpy.data.objects["Capsule"]
    assert capsule.gauss_stylization.iterations == 10  # the preset's
    assert np.abs(helpers.coords(capsule) - rest).max() > 1e-2  # stylized into its mesh (the preset's Output)


@pytest.mark.parametrize("text, message", [
    ("{not json", "Cannot read the preset"),
    ('{"lam": 2.0, "colour": "red"}', "unknown settings: colour"),
    ("[1, 2]", "is not a JSON object of settings"),
])
def test_a_bad_preset_stops_the_batch_before_it_starts(addon, tmp_path, capsys, text, message):
    preset = tmp_path / "preset.json"
    preset.write_text(text)
    mesh = os.path.join(helpers.MESHES, "small", "cube_odedstein_26.obj")
    assert _cli(addon, "batch", mesh, "--preset", preset, "--out-dir", tmp_path / "out") == 1
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
