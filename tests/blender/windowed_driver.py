"""Drive the live Stylize operator in a real Blender window (see run_windowed.sh).

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_driver.py -- BUILD_DIR

Blender ignores real input with --enable-event-simulate; every key press and
click below is simulated with Window.event_simulate, as a person would do it.
The scenario runs as a generator stepped by bpy.app.timers, so Blender's event
loop (modal ticks, redraws) runs between the steps. At the end it prints
"N passed, M failed", writes that line to BUILD_DIR/screenshots/windowed_result.txt
and quits Blender itself.
"""

import os
import statistics
import sys
import time
import traceback

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
# GAUSS_WINDOWED_MESH (relative to shared/meshes) runs the scenario on another mesh,
# e.g. bunny/bun_zipper_35947.obj to see live tick times on 35K vertices.
MESH = os.path.join(REPO, "..", "shared", "meshes",
                    os.environ.get("GAUSS_WINDOWED_MESH", "small/spot_triangulated_2930.obj"))
TIME_LIMIT = 240.0  # seconds; run_windowed.sh also wraps Blender in `timeout`

ARGV = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
BUILD = os.path.abspath(ARGV[0] if ARGV else os.path.join(REPO, "build"))
SHOTS = os.path.join(BUILD, "screenshots")

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


def center(region):
    return region.x + region.width // 2, region.y + region.height // 2


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


def coords(obj):
    out = np.empty((len(obj.data.vertices), 3), np.float32)
    obj.data.vertices.foreach_get("co", out.reshape(-1))
    return out


def live_operator():
    import gauss_stylization
    return next(iter(gauss_stylization.operators.running.values()), None)


def wait_steps(count, limit=30.0):
    """Generator: wait until the live run has done ``count`` steps."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        op = live_operator()
        if op is not None and op.session.steps >= count:
            return
        yield 0.05


def wait_stopped(limit=10.0):
    deadline = time.monotonic() + limit
    while live_operator() is not None and time.monotonic() < deadline:
        yield 0.05


def start_live_run():
    with override():
        return bpy.ops.object.gauss_stylize('INVOKE_DEFAULT')


# -- scenario -----------------------------------------------------------------------

def set_up():
    sys.path.insert(0, os.path.join(BUILD, "addon"))
    import gauss_stylization
    gauss_stylization.register()
    bpy.utils.register_class(VIEW3D_PT_gauss_tab_probe)
    for obj in list(bpy.data.objects):
        if obj.type == 'MESH':
            bpy.data.objects.remove(obj)
    bpy.ops.wm.obj_import(filepath=MESH)
    obj = bpy.context.selected_objects[0]
    bpy.context.view_layer.objects.active = obj
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
          op is not None and op.session.applied.styles[0][1] == 9.0)
    changed = not np.array_equal(coords(bpy.data.objects[name]), original)
    press('ESC', *viewport_point())
    yield from wait_stopped()
    check("Esc stops the run", live_operator() is None)
    check("mesh moved while running", changed)
    check("Esc restores the mesh bit-exactly",
          np.array_equal(coords(bpy.data.objects[name]), original))


def enter_keeps_and_undo_restores(name):
    original = coords(bpy.data.objects[name])
    start_live_run()
    yield from wait_steps(10)
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
    start_live_run()
    yield from wait_steps(3)
    press('LEFTMOUSE', *center(view3d()[1]['UI']))  # a click in the sidebar is for the panel
    yield 0.3
    check("left-click in the sidebar does not end the run", live_operator() is not None)
    press('RIGHTMOUSE', *viewport_point())
    yield from wait_stopped()
    check("right-click in the viewport cancels and restores",
          live_operator() is None and np.array_equal(coords(bpy.data.objects[name]), original))
    start_live_run()
    yield from wait_steps(3)
    press('LEFTMOUSE', *viewport_point())
    yield from wait_stopped()
    check("left-click in the viewport keeps the result",
          live_operator() is None and not np.array_equal(coords(bpy.data.objects[name]), original))


def screenshot_panel():
    os.makedirs(SHOTS, exist_ok=True)
    path = os.path.join(SHOTS, "panel.png")
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
    yield from enter_keeps_and_undo_restores(name)
    yield from mouse_buttons(name)


# -- runner -------------------------------------------------------------------------

def finish():
    failed = sum(1 for _, passed, _ in results if not passed)
    line = "%d passed, %d failed" % (len(results) - failed, failed)
    if not results:
        line = "0 passed, 1 failed"
    print("windowed:", line, flush=True)
    os.makedirs(SHOTS, exist_ok=True)
    with open(os.path.join(SHOTS, "windowed_result.txt"), "w") as handle:
        handle.write(line + "\n")
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.quit_blender()


def runner(steps, started):
    def advance():
        try:
            if time.monotonic() - started > TIME_LIMIT:
                check("scenario finished in time", False, "over %.0f s" % TIME_LIMIT)
                finish()
                return None
            delay = next(steps)
            return float(delay)
        except StopIteration:
            finish()
        except Exception:
            traceback.print_exc()
            check("scenario ran without an exception", False)
            finish()
        return None
    return advance


bpy.app.timers.register(runner(scenario(), time.monotonic()), first_interval=1.0)
