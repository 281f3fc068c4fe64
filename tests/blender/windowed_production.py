"""Windowed scenarios of New Object output and the bakes (run by windowed_driver.py).

``run(d)`` is a generator like the driver's scenarios; ``d`` is windowed_kit.py, the drivers'
helpers (press, live_run, wait_stopped, check, ...).
"""

import os
import tempfile
import time

import bpy
import numpy as np

import rig
from helpers import coords, evaluated_coords
from scene_kit import suzanne


def _addon():
    import gauss_stylization
    return gauss_stylization


def _subdivided_suzanne(d):
    """A Suzanne (507 vertices) with a Subdivision modifier: small, so the run starts fast on a busy machine."""
    with d.override():
        obj = suzanne("Subdivided", subdivisions=0)
    obj.modifiers.new("Subdivision", 'SUBSURF').levels = 1
    obj.gauss_stylization.use_modifiers = True
    obj.gauss_stylization.output = 'NEW_OBJECT'
    d.activate(obj)
    d.push_undo("Subdivided copy")
    return obj.name


def new_object_live_run(d):
    """Use Modifiers + New Object: the run writes into '<name>_stylized' live; Esc removes it,
    Enter keeps it, one Ctrl+Z takes it away again. The original never changes."""
    subdivided = _subdivided_suzanne(d)
    result_name = subdivided + _addon().settings.schema.NEW_OBJECT_SUFFIX
    original, shown = coords(bpy.data.objects[subdivided]), evaluated_coords(bpy.data.objects[subdivided])
    counts = (len(bpy.data.objects), len(bpy.data.meshes))
    yield from d.live_run(5)
    result = bpy.data.objects.get(result_name)
    d.check("a New Object run writes into '%s' live" % result_name,
            result is not None and len(result.data.vertices) == len(shown)
            and not np.array_equal(coords(result), shown))
    d.check("... with the original drawn as a wireframe meanwhile, still the active object",
            bpy.data.objects[subdivided].display_type == 'WIRE'
            and bpy.context.view_layer.objects.active == bpy.data.objects[subdivided])
    yield from screenshot_window(d, "new_object_live.png")
    d.press('ESC', *d.viewport_point())
    yield from d.wait_stopped()
    d.check("Esc removes the new object and its mesh",
            d.live_operator() is None and result_name not in bpy.data.objects
            and (len(bpy.data.objects), len(bpy.data.meshes)) == counts)
    obj = bpy.data.objects[subdivided]
    d.check("... and the original is drawn as before and bit-exactly unchanged",
            obj.display_type == 'TEXTURED' and np.array_equal(coords(obj), original)
            and np.array_equal(evaluated_coords(obj), shown))

    d.set_marker(5)
    d.activate(bpy.data.objects[subdivided])
    yield from d.live_run(5)
    d.press('RET', *d.viewport_point())
    yield from d.wait_stopped()
    result = bpy.data.objects.get(result_name)
    obj = bpy.data.objects[subdivided]
    d.check("Enter keeps the new object, selected and active, the original shown",
            result is not None and bpy.context.view_layer.objects.active == result and result.select_get()
            and obj.display_type == 'TEXTURED' and np.array_equal(coords(obj), original))
    d.press('Z', *d.viewport_point(), ctrl=True)
    yield 0.5
    d.check("one Ctrl+Z after Enter removes the new object and nothing else",
            result_name not in bpy.data.objects and d.marker() == 5
            and np.array_equal(coords(bpy.data.objects[subdivided]), original))


def _wait_bake(limit=60.0):
    deadline = time.monotonic() + limit
    while d_running() and time.monotonic() < deadline:
        yield 0.05


def d_running():
    return any(type(run).__name__.startswith("OBJECT_OT_gauss_bake") for run in _addon().run.runs.running.values())


def bakes(d):
    """Bake Animation from the panel's operator: modal, progress shown, Esc leaves nothing, a finished
    bake plays back exactly and one Ctrl+Z removes its modifier."""
    hidden = [obj.name for obj in bpy.context.view_layer.objects if not obj.hide_get()]
    for name in hidden:
        bpy.data.objects[name].hide_set(True)  # the capsule alone in the screenshots
    with d.override():
        capsule = rig.bent_capsule(frames=(1, 120), segments=(32, 16))
    folder = tempfile.mkdtemp(prefix="gauss_bake_")
    path = os.path.join(folder, "capsule.pc2")
    with d.override():
        bpy.ops.view3d.view_selected()
        bpy.ops.ed.undo_push(message="Rigged capsule")
    d.set_marker(6)
    bpy.context.scene.frame_set(30)
    with d.override():
        started = bpy.ops.object.gauss_bake_animation('INVOKE_DEFAULT', frame_start=1, frame_end=120,
                                                      filepath=path, warm_start=False)
    d.check("Bake Animation from the UI runs in the background", started == {'RUNNING_MODAL'} and d_running())
    yield 0.4
    yield from screenshot_window(d, "bake_progress.png")
    d.check("... frames go by while the UI stays responsive", d_running())
    d.press('ESC', *d.viewport_point())
    yield from _wait_bake()
    d.check("Esc cancels the bake: no file, no modifier, the frame as it was",
            not d_running() and os.listdir(folder) == [] and _addon().mesh.cache_modifier.find(capsule) is None
            and bpy.context.scene.frame_current == 30)

    with d.override():
        bpy.ops.object.gauss_bake_animation('INVOKE_DEFAULT', frame_start=41, frame_end=80, filepath=path,
                                            warm_start=False)
    yield from screenshot_window(d, "bake_running.png")
    yield from _wait_bake()
    modifier = _addon().mesh.cache_modifier.find(capsule)
    d.check("a finished bake writes the file and adds the Mesh Cache modifier last",
            os.listdir(folder) == ["capsule.pc2"] and modifier is not None and capsule.modifiers[-1] == modifier)
    frames = _addon().pc2.read(path).frames
    bpy.context.scene.frame_set(60)
    d.check("playback at frame 60 shows baked frame 60 exactly",
            len(frames) == 40 and np.array_equal(evaluated_coords(capsule), frames[60 - 41]))
    yield from screenshot_window(d, "bake_done.png")
    d.press('Z', *d.viewport_point(), ctrl=True)
    yield 0.5
    capsule = bpy.data.objects["Capsule"]
    d.check("one Ctrl+Z after the bake removes its modifier (the file stays)",
            _addon().mesh.cache_modifier.find(capsule) is None and d.marker() == 6 and os.path.isfile(path))
    os.remove(path)
    os.rmdir(folder)
    for name in ("Capsule", "Rig"):
        bpy.data.objects.remove(bpy.data.objects[name])
    for name in hidden:
        bpy.data.objects[name].hide_set(False)


def screenshot_window(d, filename):
    os.makedirs(d.SHOTS, exist_ok=True)
    path = os.path.join(d.SHOTS, filename)
    if os.path.exists(path):
        os.remove(path)
    yield 0.3
    with bpy.context.temp_override(window=d.window()):
        bpy.ops.screen.screenshot(filepath=path)
    d.check("screenshot %s saved" % filename, os.path.isfile(path), path)


def run(d):
    yield from new_object_live_run(d)
    yield from bakes(d)
