"""What a redraw of the 3D view costs on a large mesh, with and without the add-on's drawing,
idle and during a live run (Blender 3.4 in a window under Xvfb; informational, no assertion):

    xvfb-run -a -s "-screen 0 1280x800x24" blender --factory-startup -P tests/blender/measure_draw.py -- BUILD_DIR [LEVELS]

The 35K bunny subdivided LEVELS times (default 2: about 575K vertices). Each figure is the median of
wm.redraw_timer('DRAW') over REPEATS redraws of the 3D view's main region, and of the add-on's
two draw callbacks as timed around them. Prints lines "draw ms ..." and quits.
"""

import os
import statistics
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
ARGV = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
os.environ["GAUSS_BUILD_DIR"] = os.path.abspath(ARGV[0]) if ARGV else ""
LEVELS = int(ARGV[1]) if len(ARGV) > 1 else 2
REPEATS = 10
bpy.context.preferences.view.show_splash = False

import helpers  # noqa: E402  (puts the add-on on sys.path)


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == 'VIEW_3D')
    region = next(r for r in area.regions if r.type == 'WINDOW')
    return window, area, region


def redraw_ms():
    window, area, region = view3d()
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        with bpy.context.temp_override(window=window, area=area, region=region):
            bpy.ops.wm.redraw_timer(type='DRAW', iterations=1)
        times.append(1000.0 * (time.perf_counter() - start))
    return statistics.median(times)


callback_ms = {}


def timed(handler):
    draw = handler.draw

    def wrapped():
        start = time.perf_counter()
        draw()
        callback_ms.setdefault(handler.title, []).append(1000.0 * (time.perf_counter() - start))
    handler.draw = wrapped


def report(what):
    line = "draw ms %-34s view %.1f" % (what, redraw_ms())
    for title, times in sorted(callback_ms.items()):
        line += ", %s %.1f" % (title, statistics.median(times) if times else float("nan"))
    callback_ms.clear()
    print(line, flush=True)


def scenario():
    import gauss_stylization
    from gauss_stylization.handles import handle_tool
    from gauss_stylization.sphere import sphere_overlay
    gauss_stylization.register()
    for obj in list(bpy.data.objects):
        if obj.type == 'MESH':
            bpy.data.objects.remove(obj)
    obj = helpers.import_obj("bunny/bun_zipper_35947.obj")
    modifier = obj.modifiers.new("Subdivision", 'SUBSURF')
    modifier.levels = LEVELS
    window, area, region = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region, object=obj, active_object=obj):
        bpy.ops.object.modifier_apply(modifier=modifier.name)
        bpy.ops.view3d.view_selected()
    print("mesh: %d vertices" % len(obj.data.vertices), flush=True)
    timed(sphere_overlay._handler)
    timed(handle_tool._handler)
    yield 1.0
    helpers.add_slot(obj, 'CUBE')
    settings = obj.gauss_stylization

    def drawing(on):
        for handler in (handle_tool._handler, sphere_overlay._handler):
            handler.add() if on else handler.remove()

    # Each condition twice, interleaved, so a slow first redraw or a busy machine shows as a disagreement.
    for _ in range(2):
        drawing(False)
        report("idle, no add-on drawing")
        drawing(True)
        settings.show_gauss_sphere = False
        report("idle, add-on drawing, sphere off")
        settings.show_gauss_sphere = True
        report("idle, Gauss sphere on")
    settings.show_gauss_sphere = False
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.object.gauss_stylize('INVOKE_DEFAULT')
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline:
        op = next(iter(gauss_stylization.run.runs.running.values()), None)
        if op is not None and op.session is not None and op.session.steps >= 2:
            break
        yield 0.2
    for _ in range(2):
        settings.show_gauss_sphere = False
        report("live run, Gauss sphere off")
        settings.show_gauss_sphere = True
        report("live run, Gauss sphere on")
    op = next(iter(gauss_stylization.run.runs.running.values()), None)
    if op is not None:
        print("live run: median step %.0f ms, tick %.0f ms" % (statistics.median(op.session.step_ms),
                                                                statistics.median(op.tick_ms)), flush=True)
    with bpy.context.temp_override(window=window):
        bpy.ops.wm.quit_blender()


steps = scenario()


def advance():
    try:
        return next(steps)
    except StopIteration:
        return None


bpy.app.timers.register(advance, first_interval=1.0)
