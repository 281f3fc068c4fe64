"""Drive the live Stylize operator in a real Blender window (see run_windowed.sh).

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_driver.py -- BUILD_DIR

Blender ignores real input with --enable-event-simulate; every key press and
click below is simulated with Window.event_simulate, as a person would do it.
The scenario runs as a generator stepped by bpy.app.timers, so Blender's event
loop (modal ticks, redraws) runs between the steps. At the end it prints
"N passed, M failed", writes that line to BUILD_DIR/screenshots/windowed_result.txt
and quits Blender itself. Other drivers (windowed_live_run.py) import the helpers
and run their own scenarios with start().
"""

import os
import statistics
import sys
import tempfile
import time
import traceback
import types

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
ARGV = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
BUILD = os.path.abspath(ARGV[0] if ARGV else os.path.join(REPO, "build"))
SHOTS = os.path.join(BUILD, "screenshots")
os.environ["GAUSS_BUILD_DIR"] = BUILD  # helpers load the add-on from there
sys.path.insert(0, HERE)
from helpers import coords, key_coords, mesh_coords  # noqa: E402  (the same measurements as headless)
from scene_kit import activate, import_obj  # noqa: E402  (helpers put blender_scenes on sys.path)
import windowed_production  # noqa: E402
# GAUSS_WINDOWED_MESH (relative to shared/meshes) runs the scenario on another mesh,
# e.g. bunny/bun_zipper_35947.obj to see live tick times on 35K vertices.
MESH = os.path.join(REPO, "..", "shared", "meshes",
                    os.environ.get("GAUSS_WINDOWED_MESH", "small/spot_triangulated_2930.obj"))
TIME_LIMIT = 360.0  # seconds; run_windowed.sh also wraps Blender in `timeout` (a busy machine is slow)

# Scripts given with -P run before the splash screen opens; turning it off here
# keeps it out of the screenshot (factory startup: nothing is saved).
bpy.context.preferences.view.show_splash = False

results = []  # (name, passed, detail)
drawn = {"gauss_tab": 0.0}


def check(name, passed, detail=""):
    results.append((name, bool(passed), detail))
    print("%s: %s %s" % ("PASS" if passed else "FAIL", name, detail), flush=True)


class VIEW3D_PT_gauss_tab_probe(bpy.types.Panel):
    """Drawn only while the sidebar shows the Gauss tab: tells the driver it is open.
    Unregistered again once the tab is found, so the screenshot shows only the add-on."""
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Gauss"
    bl_label = "Driver Probe"

    def draw(self, context):
        drawn["gauss_tab"] = time.monotonic()


# -- helpers ----------------------------------------------------------------------

def window():
    return bpy.context.window_manager.windows[0]


def view3d():
    area = next(a for a in window().screen.areas if a.type == 'VIEW_3D')
    regions = {r.type: r for r in area.regions}
    return area, regions


def override():
    area, regions = view3d()
    return bpy.context.temp_override(window=window(), area=area, region=regions['WINDOW'])


def viewport_point():
    """A point in the 3D view's drawing region, left of the sidebar."""
    area, regions = view3d()
    main = regions['WINDOW']
    return main.x + (regions['UI'].x - main.x) // 2, main.y + main.height // 2


def press(event_type, x, y, **modifiers):
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    win.event_simulate(type=event_type, value='PRESS', x=x, y=y, **modifiers)
    win.event_simulate(type=event_type, value='RELEASE', x=x, y=y, **modifiers)


def shape(obj):
    """All a cancel must put back: vertices, every shape key (name, coordinates, value), active key."""
    keys = obj.data.shape_keys
    blocks = [(k.name, key_coords(k), k.value) for k in keys.key_blocks] if keys else []
    return coords(obj), blocks, obj.active_shape_key_index


def same_shape(a, b):
    return (np.array_equal(a[0], b[0]) and a[2] == b[2] and len(a[1]) == len(b[1])
            and all(na == nb and np.array_equal(ca, cb) and va == vb
                    for (na, ca, va), (nb, cb, vb) in zip(a[1], b[1])))


def push_undo(message):
    with override():
        bpy.ops.ed.undo_push(message=message)


def set_marker(value):
    """An undo step whose only change (scene["gauss_marker"]) shows where an undo went."""
    bpy.context.scene["gauss_marker"] = value
    push_undo("Marker %d" % value)


def marker():
    return bpy.context.scene.get("gauss_marker")


reports_read = [0]


def new_reports():
    """Reports Blender showed the artist since the last call, as the Info editor lists them."""
    area = next(a for a in window().screen.areas if a.type == 'DOPESHEET_EDITOR')  # the timeline
    ui_type = area.ui_type
    area.type = 'INFO'
    region = next(r for r in area.regions if r.type == 'WINDOW')
    with bpy.context.temp_override(window=window(), area=area, region=region):
        bpy.ops.info.select_all(action='SELECT')
        bpy.ops.info.report_copy()
    area.ui_type = ui_type
    lines = bpy.context.window_manager.clipboard.splitlines()
    fresh = lines[reports_read[0]:]
    reports_read[0] = len(lines)
    return "\n".join(fresh)


def live_operator():
    import gauss_stylization
    return next(iter(gauss_stylization.run.runs.running.values()), None)


def wait_steps(count, limit=30.0):
    """Generator: wait until the live run has done ``count`` steps or its object has converged (a
    converged object is not stepped until something changes: the run goes on without steps)."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        op = live_operator()
        if op is not None and op.session is not None and (op.session.steps >= count or op.session.converged):
            return
        yield 0.05


def wait_stopped(limit=10.0):
    deadline = time.monotonic() + limit
    while live_operator() is not None and time.monotonic() < deadline:
        yield 0.05


def start_live_run():
    with override():
        return bpy.ops.object.gauss_stylize('INVOKE_DEFAULT')


def live_run(steps):
    """Generator: start a live run from the 3D view and wait until it has done ``steps`` steps."""
    start_live_run()
    yield from wait_steps(steps)


def goes_on(name, more=3):
    """Generator: check ``name`` = the live run does ``more`` further steps."""
    op = live_operator()
    steps = op.session.steps if op and op.session else 0
    yield from wait_steps(steps + more)
    op = live_operator()
    check(name, op is not None and op.session is not None and
          (op.session.steps >= steps + more or op.session.converged))


def end_with(key, name, obj_name, expected):
    """Generator: press ``key`` over the viewport, wait for the run to end, and check
    ``name`` = it ended and ``obj_name``'s vertices equal ``expected`` bit for bit."""
    press(key, *viewport_point())
    yield from wait_stopped()
    check(name, live_operator() is None and np.array_equal(coords(bpy.data.objects[obj_name]), expected))


# -- scenario -----------------------------------------------------------------------

def set_up():
    import gauss_stylization  # helpers put BUILD/addon on sys.path
    gauss_stylization.register()
    bpy.utils.register_class(VIEW3D_PT_gauss_tab_probe)
    for obj in list(bpy.data.objects):
        if obj.type == 'MESH':
            bpy.data.objects.remove(obj)
    obj = import_obj(MESH)
    area, regions = view3d()
    area.spaces.active.show_region_ui = True
    with override():
        bpy.ops.view3d.view_selected()
        bpy.ops.ed.undo_push(message="Driver set-up")  # the state Ctrl+Z must return to
    return obj.name


def open_gauss_tab():
    """The mouse wheel over the sidebar's tab strip cycles the tabs until Gauss is drawn."""
    ui = view3d()[1]['UI']
    x, y = ui.x + ui.width - 8, ui.y + ui.height // 2  # the tabs run along the right edge
    for _ in range(12):
        asked = time.monotonic()
        yield 0.4
        if drawn["gauss_tab"] > asked:
            break
        window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        window().event_simulate(type='WHEELDOWNMOUSE', value='PRESS', x=x, y=y)
    check("sidebar shows the Gauss tab", drawn["gauss_tab"] > asked)
    bpy.utils.unregister_class(VIEW3D_PT_gauss_tab_probe)


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
    name = set_up()
    yield 1.0  # first redraws
    yield from open_gauss_tab()
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
    yield from windowed_production.run(types.SimpleNamespace(**globals()))
    yield from save_and_reopen_mid_run(name)  # last: it replaces the whole file


# -- runner -------------------------------------------------------------------------

def finish(result_name="windowed_result.txt"):
    failed = sum(1 for _, passed, _ in results if not passed)
    line = "%d passed, %d failed" % (len(results) - failed, failed)
    if not results:
        line = "0 passed, 1 failed"
    print("windowed:", line, flush=True)
    os.makedirs(SHOTS, exist_ok=True)
    with open(os.path.join(SHOTS, result_name), "w") as handle:
        handle.write(line + "\n")
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.quit_blender()


def runner(steps, started, result_name="windowed_result.txt", time_limit=TIME_LIMIT):
    """A bpy.app.timers callback stepping the scenario generator ``steps``; at the end (or after
    ``time_limit`` seconds, or on an exception) the summary goes to BUILD_DIR/screenshots/``result_name``."""
    def advance():
        try:
            if time.monotonic() - started > time_limit:
                check("scenario finished in time", False, "over %.0f s" % time_limit)
                finish(result_name)
                return None
            delay = next(steps)
            return float(delay)
        except StopIteration:
            finish(result_name)
        except Exception:
            traceback.print_exc()
            check("scenario ran without an exception", False)
            finish(result_name)
        return None
    return advance


def start(scenario_steps, result_name="windowed_result.txt", time_limit=TIME_LIMIT):
    # Persistent: loading a file (save_and_reopen_mid_run) removes all other timers.
    bpy.app.timers.register(runner(scenario_steps, time.monotonic(), result_name, time_limit),
                            first_interval=1.0, persistent=True)


if __name__ == "__main__":  # run by Blender with -P; other drivers import the helpers above
    start(scenario())
