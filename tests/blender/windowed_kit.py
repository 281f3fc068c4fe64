"""The kit of the windowed drivers (run_windowed.sh): a real Blender window driven as a person would.

    import windowed_kit as d          # at the top of a driver run with blender -P DRIVER.py -- BUILD_DIR
    d.start(scenario())               # scenario(): a generator of the seconds to wait between steps

Blender ignores real input with --enable-event-simulate; every key press and click is simulated with
Window.event_simulate. A scenario runs as a generator stepped by bpy.app.timers, so Blender's event
loop (modal ticks, redraws) runs between the steps. check() records a result; at the end start()'s
runner prints "N passed, M failed", writes that line to BUILD_DIR/screenshots/RESULT_NAME and quits
Blender. Importing the kit sets up the paths (the add-on staged in BUILD_DIR, the tests' helpers) and
the window options. cube_style_scenarios() is the start that windowed_live_run.py, windowed_run_endings.py
and windowed_undo_save.py share: the test mesh with a Cube style slot, then their scenarios by name.
"""

import os
import sys
import time
import traceback

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
ARGV = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
BUILD = os.path.abspath(ARGV[0] if ARGV else os.path.join(REPO, "build"))
SHOTS = os.path.join(BUILD, "screenshots")
os.environ["GAUSS_BUILD_DIR"] = BUILD  # helpers load the add-on from there
sys.path.insert(0, HERE)
# The same measurements as headless, and the demo scenes' activate(); mesh_coords and activate are for the drivers.
from helpers import coords, key_coords, mesh_coords  # noqa: E402,F401
from scene_kit import activate, import_obj  # noqa: E402,F401  (helpers put blender_scenes on sys.path)
# GAUSS_WINDOWED_MESH (relative to shared/meshes) runs the scenario on another mesh,
# e.g. bunny/bun_zipper_35947.obj to see live tick times on 35K vertices.
MESH = os.path.join(REPO, "..", "shared", "meshes",
                    os.environ.get("GAUSS_WINDOWED_MESH", "small/spot_triangulated_2930.obj"))
TIME_LIMIT = 360.0  # seconds, unless a driver gives its own; run_windowed.sh also wraps Blender in `timeout`

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


def addon():
    import gauss_stylization  # the kit put BUILD/addon on sys.path (helpers)
    return gauss_stylization


def live_operator():
    return next(iter(addon().run.runs.running.values()), None)


def wait_steps(count, limit=30.0):
    """Generator: wait until the live run has done ``count`` steps or its object has converged (a
    converged object is not stepped until something changes: the run goes on without steps)."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        op = live_operator()
        if op is not None and op.session is not None and (op.session.steps >= count or op.session.at_rest):
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
          (op.session.steps >= steps + more or op.session.at_rest))


def end_with(key, name, obj_name, expected):
    """Generator: press ``key`` over the viewport, wait for the run to end, and check
    ``name`` = it ended and ``obj_name``'s vertices equal ``expected`` bit for bit."""
    press(key, *viewport_point())
    yield from wait_stopped()
    check(name, live_operator() is None and np.array_equal(coords(bpy.data.objects[obj_name]), expected))


# -- the scene ---------------------------------------------------------------------

def set_up():
    """The add-on registered, the test mesh (MESH) alone in the scene, framed in the 3D view with the
    sidebar open, and an undo step; returns the mesh object's name."""
    addon().register()
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


def cube_style_scenarios(scenarios, run, on_demand=(), prepare=None):
    """Generator: set_up(), the Gauss tab opened, a Cube style slot on the test mesh and an undo step
    for it; then ``prepared = prepare(name)`` if given, and each of ``scenarios`` in order as
    ``run(scenario_name, name, prepared)``, which returns the scenario's generator. Returns the seconds
    taken. GAUSS_WINDOWED_ONLY=name,name runs only the scenarios named (while working on one);
    ``on_demand`` scenarios run first, and only when named there."""
    started = time.monotonic()
    name = set_up()
    yield 1.0  # first redraws
    yield from open_gauss_tab()
    addon().settings_io.add_slot(bpy.data.objects[name].gauss_stylization, {"preset": 'CUBE'})
    push_undo("Cube style")
    prepared = prepare(name) if prepare is not None else None
    only = [n for n in os.environ.get("GAUSS_WINDOWED_ONLY", "").split(",") if n]
    for scenario_name in tuple(on_demand) + tuple(scenarios):
        if (only or scenario_name in on_demand) and scenario_name not in only:
            continue
        print("-- %s (%.0f s)" % (scenario_name, time.monotonic() - started), flush=True)
        yield from run(scenario_name, name, prepared)
    return time.monotonic() - started


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
