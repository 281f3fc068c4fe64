"""Drive the live Stylize operator in a real Blender window (see run_windowed.sh): the basics.

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_driver.py -- BUILD_DIR

Keys and clicks that end a run, a switch to Cubic mid-run, shape keys, deleting things, closing the
run's viewport, New Object output and the bakes (windowed_production.py), saving and reopening. Every
key press and click is simulated as a person would do it, with windowed_kit.py's helpers. At the end it
prints "N passed, M failed" and writes that line to BUILD_DIR/screenshots/windowed_result.txt.
"""

import os
import statistics
import sys
import tempfile

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_kit import (  # noqa: E402
    SHOTS, check, coords, end_with, goes_on, key_coords, live_operator, live_run, mesh_coords, new_reports,
    override, press, push_undo, same_shape, shape, start_live_run, view3d, viewport_point, wait_steps,
    wait_stopped, window)
from scene_kit import activate  # noqa: E402
import windowed_production  # noqa: E402


# -- scenario -----------------------------------------------------------------------

def esc_cancels_and_restores(name):
    original = coords(bpy.data.objects[name])
    check("invoke from the UI runs modal", start_live_run() == {'RUNNING_MODAL'})
    yield from wait_steps(5)
    op = live_operator()
    check("live run ticks", op is not None and op.session.steps >= 5,
          "steps=%s" % (op.session.steps if op else None))
    slot = bpy.data.objects[name].gauss_stylization.styles[0]
    slot.sigma = 9.0  # as if typed into the panel
    steps_at_change = op.session.steps if op else 0
    yield from wait_steps(steps_at_change + 3)
    check("sigma changed mid-run reaches the solver",
          op is not None and op.session.applied["styles"][0]["sigma"] == 9.0)
    changed = not np.array_equal(coords(bpy.data.objects[name]), original)
    press('ESC', *viewport_point())
    yield from wait_stopped()
    check("Esc stops the run", live_operator() is None)
    check("mesh moved while running", changed)
    check("Esc restores the mesh bit-exactly",
          np.array_equal(coords(bpy.data.objects[name]), original))


def cubic_switch_mid_run(name):
    """Method switched to Cubic in the panel during a live run: the next steps are cubic, no new set-up;
    the panel shows Cubic Lambda and its note (screenshot panel_cubic.png); Esc restores."""
    obj = bpy.data.objects[name]
    original = coords(obj)
    yield from live_run(3)
    op = live_operator()
    factorizations = op.session.solver.factorization_count if op else None
    obj.gauss_stylization.method = 'CUBIC'  # as if picked in the Method selector
    yield from goes_on("live run goes on after switching to Cubic")
    check("the switch reaches the solver without a new set-up",
          op is not None and op.session.solver.method == "cubic"
          and op.session.solver.factorization_count == factorizations)
    yield from screenshot_panel("panel_cubic.png")
    yield from end_with('ESC', "Esc after a switch to Cubic restores the mesh bit-exactly", name, original)
    obj.gauss_stylization.method = 'GAUSS'


def enter_keeps_and_undo_restores(name):
    original = coords(bpy.data.objects[name])
    yield from live_run(10)
    yield from screenshot_panel()
    yield from wait_steps(20)
    op = live_operator()
    if op is not None and op.tick_ms:
        print("live modal tick (%d vertices): median %.2f ms, solver step median %.2f ms, %d ticks"
              % (len(original), statistics.median(op.tick_ms),
                 statistics.median(op.session.step_ms), len(op.tick_ms)))
    press('RET', *viewport_point())
    yield from wait_stopped()
    kept = coords(bpy.data.objects[name])
    check("Enter keeps the result", live_operator() is None and not np.array_equal(kept, original))
    last = bpy.context.window_manager.operators[-1] if bpy.context.window_manager.operators else None
    check("redo panel offers the iteration count",
          last is not None and last.bl_idname == "OBJECT_OT_gauss_stylize"
          and last.properties.iterations >= 20,
          "iterations=%s" % (last.properties.iterations if last else None))
    with override():
        bpy.ops.ed.undo()
    yield 0.3
    check("Ctrl+Z after Enter brings the original back",
          np.array_equal(coords(bpy.data.objects[name]), original))


def mouse_buttons(name):
    original = coords(bpy.data.objects[name])
    yield from live_run(3)
    # A click in the sidebar is for the panel. It goes on the run's box of text lines at the top, where
    # no button is: the sidebar's centre lands on whichever row is there (a dropdown whose menu would
    # take the next click), its edge on the handle that resizes it.
    sidebar = view3d()[1]['UI']
    press('LEFTMOUSE', sidebar.x + sidebar.width // 2, sidebar.y + sidebar.height - 130)
    yield 0.3
    check("left-click in the sidebar does not end the run", live_operator() is not None)
    yield from end_with('RIGHTMOUSE', "right-click in the viewport cancels and restores", name, original)
    yield from live_run(3)
    press('LEFTMOUSE', *viewport_point())
    yield from wait_stopped()
    check("left-click in the viewport keeps the result",
          live_operator() is None and not np.array_equal(coords(bpy.data.objects[name]), original))


def make_keyed_copy(name):
    """A copy of the test mesh with shape keys Basis and Smile (half on), active and selected."""
    source = bpy.data.objects[name]
    obj = source.copy()
    obj.data = source.data.copy()
    obj.name = "Keyed"
    bpy.context.scene.collection.objects.link(obj)
    obj.shape_key_add(name="Basis", from_mix=False)
    smile = obj.shape_key_add(name="Smile", from_mix=False)
    smile.data.foreach_set("co", (key_coords(smile) + np.float32(0.05)).reshape(-1))
    smile.value = 0.5
    obj.active_shape_key_index = 0
    activate(obj)
    push_undo("Keyed copy")
    return obj.name


def keyed_mesh_esc_restores(keyed):
    for output in ('MESH', 'SHAPE_KEY'):
        obj = bpy.data.objects[keyed]
        obj.gauss_stylization.output = output
        before = shape(obj)
        yield from live_run(5)
        changed = not same_shape(shape(bpy.data.objects[keyed]), before)
        press('ESC', *viewport_point())
        yield from wait_stopped()
        check("Esc restores a mesh with shape keys bit-exactly (%s output)" % output,
              live_operator() is None and changed and same_shape(shape(bpy.data.objects[keyed]), before))


def shape_keys_deleted_mid_run(keyed):
    """Shape Keys panel > Delete All Shape Keys during a run: removing the key being written must not
    crash Blender."""
    new_reports()
    obj = bpy.data.objects[keyed]
    obj.gauss_stylization.output = 'MESH'
    original = coords(obj)
    yield from live_run(3)
    with override():
        bpy.ops.object.shape_key_remove(all=True)
    yield from goes_on("deleting the shape keys during a Mesh-output run lets it go on")
    yield from end_with('ESC', "Esc then restores the vertices bit-exactly", keyed, original)

    obj.gauss_stylization.output = 'SHAPE_KEY'
    yield from live_run(3)
    with override():
        bpy.ops.object.shape_key_remove(all=True)
    yield from wait_stopped()
    obj = bpy.data.objects[keyed]
    text = new_reports()
    check("deleting the shape keys during a Shape-Key-output run stops it with a report",
          live_operator() is None and "was deleted or renamed" in text, repr(text[-200:]))
    check("... and leaves the mesh bit-exact without shape keys",
          obj.data.shape_keys is None and np.array_equal(coords(obj), original))
    press('ESC', *viewport_point())  # close the error report's popup, which takes the keys
    yield 0.3


def object_removed_by_script_mid_run(keyed):
    """An add-on script removes the object from a timer callback during a run."""
    obj = bpy.data.objects[keyed]
    obj.gauss_stylization.output = 'SHAPE_KEY'
    mesh_name, original = obj.data.name, coords(obj)
    objects = len(bpy.data.objects)
    yield from live_run(5)
    changed = bpy.data.objects[keyed].data.shape_keys is not None
    bpy.data.objects.remove(bpy.data.objects[keyed])  # (this generator step is a bpy.app.timers callback)
    yield from wait_stopped()
    yield 0.2
    text = new_reports()
    check("removing the object by script during a run stops it with a report",
          live_operator() is None and "object was deleted" in text, repr(text[-200:]))
    mesh = bpy.data.meshes[mesh_name]
    check("... its mesh is restored bit-exactly and the keys the run added are removed",
          changed and mesh.shape_keys is None and np.array_equal(mesh_coords(mesh), original)
          and len(bpy.data.objects) == objects - 1)


def delete_key_mid_run(name):
    """The artist presses Delete over the viewport during a run, then Ctrl+Z."""
    activate(bpy.data.objects[name])
    push_undo("Before Delete")
    original = coords(bpy.data.objects[name])
    yield from live_run(5)
    press('DEL', *viewport_point())
    yield from wait_stopped()
    yield 0.2
    text = new_reports()
    check("Delete during a run deletes the object and stops the run with a report",
          live_operator() is None and name not in bpy.data.objects and "object was deleted" in text,
          repr(text[-200:]))
    press('Z', *viewport_point(), ctrl=True)
    yield 0.5
    obj = bpy.data.objects.get(name)
    check("Ctrl+Z brings the object back with its mesh bit-exactly as before the run",
          obj is not None and np.array_equal(coords(obj), original))


def viewport_closed_mid_run(name):
    """The 3D view the run was started in is closed (areas joined) during the run."""
    area, regions = view3d()
    with bpy.context.temp_override(window=window(), area=area, region=regions['WINDOW']):
        bpy.ops.screen.area_split(direction='VERTICAL', factor=0.5)
    views = [a for a in window().screen.areas if a.type == 'VIEW_3D']
    check("a second 3D view was opened", len(views) == 2)
    activate(bpy.data.objects[name])
    original = coords(bpy.data.objects[name])
    run_in = views[-1]
    region = next(r for r in run_in.regions if r.type == 'WINDOW')
    with bpy.context.temp_override(window=window(), area=run_in, region=region):
        bpy.ops.object.gauss_stylize('INVOKE_DEFAULT')
    yield from wait_steps(3)
    with bpy.context.temp_override(window=window(), area=run_in):
        bpy.ops.screen.area_close()
    yield from goes_on("closing the run's 3D view lets the run go on")
    yield from end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)


def save_and_reopen_mid_run(name):
    path = os.path.join(tempfile.mkdtemp(prefix="gauss_windowed_"), "mid_run.blend")
    activate(bpy.data.objects[name])
    saved = coords(bpy.data.objects[name])  # a run is not saved until it is kept
    yield from live_run(5)
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.save_as_mainfile(filepath=path)
    yield from goes_on("saving during a run lets the run go on")
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.open_mainfile(filepath=path)
    check("opening a file during a run ends the run", live_operator() is None)
    yield 0.5
    obj = bpy.data.objects.get(name)
    reopened = coords(obj) if obj is not None else None
    check("the reopened file holds exactly the mesh as it was before the run",
          reopened is not None and np.array_equal(reopened, saved))
    activate(bpy.data.objects[name])
    check("a new run starts in the reopened file", start_live_run() == {'RUNNING_MODAL'})
    yield from wait_steps(3)
    yield from end_with('ESC', "Esc in the reopened file restores the mesh bit-exactly", name, saved)
    os.remove(path)


def screenshot_panel(filename="panel.png"):
    os.makedirs(SHOTS, exist_ok=True)
    path = os.path.join(SHOTS, filename)
    if os.path.exists(path):
        os.remove(path)
    yield 0.3  # let the header text and panel redraw first
    area, regions = view3d()
    with bpy.context.temp_override(window=window(), area=area):
        bpy.ops.screen.screenshot_area(filepath=path)
    check("screenshot of the Gauss panel saved", os.path.getsize(path) > 10000 if os.path.exists(path) else False,
          path)


def scenario():
    name = kit.set_up()
    yield 1.0  # first redraws
    yield from kit.open_gauss_tab()
    yield from esc_cancels_and_restores(name)
    yield from cubic_switch_mid_run(name)
    yield from enter_keeps_and_undo_restores(name)
    yield from mouse_buttons(name)
    # Ctrl+Z and Edit > Undo during a run, saving during a run: windowed_undo_save.py.
    keyed = make_keyed_copy(name)
    yield from keyed_mesh_esc_restores(keyed)
    yield from shape_keys_deleted_mid_run(keyed)
    yield from object_removed_by_script_mid_run(keyed)
    yield from delete_key_mid_run(name)
    yield from viewport_closed_mid_run(name)
    yield from windowed_production.run(kit)
    yield from save_and_reopen_mid_run(name)  # last: it replaces the whole file


kit.start(scenario())
