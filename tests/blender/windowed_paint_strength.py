"""Painted strength in a real window: Weight Paint strokes during a live run are picked up when the
object returns to Object Mode, and Weight Paint is reached mid-run the ways docs/interactive.md names.
Run by run_windowed.sh, with windowed_kit.py's helpers:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_paint_strength.py -- BUILD_DIR

The test mesh's Cube slot gets a Region whose weights are all 0 (Other Faces left at its default), so
the run starts with nothing to stylize.
- paint_and_return: the object goes to Weight Paint mid-run (object.mode_set, as a script would), the
  Region is set to 1 there, and back in Object Mode the run must stylize; Esc must still restore the mesh.
- the_documented_ways: Ctrl+Tab (the mode pie, Weight Paint picked with the mouse), a real stroke
  (a left-drag paints, and does not keep the run), Ctrl+Tab back; the header's mode menu there and
  back; the sidebar's Paint Region button there and back. While painting the status bar's hints say
  what clicks do. Screenshots: BUILD_DIR/screenshots/weight_paint_mid_run.png (the window while
  painting) and sidebar_paint_region.png (the 3D view with its sidebar).
The summary goes to BUILD_DIR/screenshots/windowed_paint_strength_result.txt.
"""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_kit import check, coords, end_with, live_operator, live_run, wait_steps, window  # noqa: E402
from windowed_actions import area_screenshot  # noqa: E402
import helpers  # noqa: E402

TIME_LIMIT = 900.0  # seconds: a busy 2-core machine redraws a window slowly (and paints slowly)
CUBE = np.vstack([np.eye(3), -np.eye(3)])


def unpainted_region(name):
    obj = bpy.data.objects[name]
    helpers.add_group(obj, "Paint", range(len(obj.data.vertices)), weight=0.0)
    obj.gauss_stylization.styles[0].vertex_group = "Paint"  # Other Faces: its default paints the only slot
    kit.push_undo("Paint region")


def set_mode(mode):
    with kit.override():
        bpy.ops.object.mode_set(mode=mode)


def paint_and_return(name, _prepared):
    obj = bpy.data.objects[name]
    original = coords(obj)
    rest_share = helpers.aligned_share(obj, CUBE, original)
    yield from live_run(3)
    check("a Region of weight 0 leaves the mesh unstyled",
          helpers.aligned_share(obj, CUBE) < rest_share + 0.02)
    set_mode('WEIGHT_PAINT')
    yield 0.3
    obj.vertex_groups["Paint"].add(list(range(len(original))), 1.0, 'REPLACE')  # the strokes
    op = live_operator()
    painted_at = op.session.steps if op and op.session else 0
    yield 1.0
    op = live_operator()
    check("the run goes on in Weight Paint mode without reading the strokes",
          op is not None and op.session is not None and obj.mode == 'WEIGHT_PAINT' and
          not np.any(op.session.weights["Paint"]))
    set_mode('OBJECT')
    yield 0.5  # a few ticks: the first one back reads the strokes (until then the run is still converged)
    yield from wait_steps(painted_at + 25)
    op = live_operator()
    check("back in Object Mode the run stylizes with the painted weights",
          op is not None and np.all(op.session.weights["Paint"] == 1.0) and
          helpers.aligned_share(obj, CUBE) > rest_share + 0.2,
          "share %.3f (rest %.3f)" % (helpers.aligned_share(obj, CUBE), rest_share))
    yield from end_with('ESC', "Esc after painting restores the mesh", name, original)


def _run_goes_on(obj, mode):
    op = live_operator()
    return op is not None and op.session is not None and obj.mode == mode


def _ctrl_tab_pie(dx, dy):
    """Generator: Ctrl+Tab over the viewport opens the mode pie; the mouse moved by (dx, dy) from
    where it opened and a click picks the item in that direction."""
    x, y = kit.viewport_point()
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.1
    win.event_simulate(type='TAB', value='PRESS', x=x, y=y, ctrl=True)
    win.event_simulate(type='TAB', value='RELEASE', x=x, y=y, ctrl=True)
    yield 0.5
    for i in range(1, 6):
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + dx * i // 5, y=y + dy * i // 5)
        yield 0.05
    kit.press('LEFTMOUSE', x + dx, y + dy)
    yield 0.8


def _header_mode_menu(letter):
    """Generator: a click on the viewport header's mode menu (right of the editor-type button), then
    the item's underlined letter (W: Weight Paint, O: Object Mode)."""
    header = kit.view3d()[1]['HEADER']
    x = header.x + int(100 * bpy.context.preferences.system.ui_scale)
    y = header.y + header.height // 2
    kit.press('LEFTMOUSE', x, y)
    yield 0.6
    kit.press(letter, x, y - 40)
    yield 0.8


def _operator_under_mouse(x, y):
    """Generator: the mouse to (x, y); found["command"] = the Python command of the button there."""
    area, regions = kit.view3d()
    window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.02
    bpy.context.window_manager.clipboard = ""
    try:
        with bpy.context.temp_override(window=window(), area=area, region=regions['UI']):
            bpy.ops.ui.copy_python_command_button()
    except RuntimeError:  # no operator button under the mouse
        pass
    found["command"] = bpy.context.window_manager.clipboard


found = {}


def _click_sidebar_button(idname):
    """Generator: hover down the sidebar until Blender says the button of ``idname`` is under the
    mouse, and click it there; found["clicked"] says whether it was found."""
    ui = kit.view3d()[1]['UI']
    x = ui.x + ui.width // 2
    row = int(18 * bpy.context.preferences.system.ui_scale)
    found["clicked"] = False
    known = [found[idname]] if idname in found else []  # where it was last time first
    # Every button row is hit once going down from the top (the run's rows come first).
    for y in known + list(range(ui.y + ui.height - row // 2, ui.y, -row)):
        yield from _operator_under_mouse(x, y)
        if idname in found["command"]:
            kit.press('LEFTMOUSE', x, y)
            found["clicked"], found[idname] = True, y
            yield 0.8
            return


def _stroke(x, y, dx, steps=20):
    """A left-drag from (x, y) by dx, its events queued at once: the paint stroke runs as a modal
    operator, and the scenario's timer must not be needed to end it."""
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y)
    for i in range(1, steps + 1):
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + dx * i // steps, y=y)
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x + dx, y=y)


def _screenshot(name, whole_window=False):
    path = os.path.join(kit.SHOTS, name)
    if whole_window:
        with bpy.context.temp_override(window=window()):
            bpy.ops.screen.screenshot(filepath=path)
    else:
        area_screenshot(path)
    check("screenshot %s saved" % name, os.path.exists(path) and os.path.getsize(path) > 10000)


def the_documented_ways(name, _prepared):
    obj = bpy.data.objects[name]
    original = coords(obj)
    obj.vertex_groups["Paint"].add(list(range(len(original))), 0.0, 'REPLACE')  # what the stroke paints shows
    op_class = kit.addon().operators
    paint = kit.addon().operators.PAINT_HINTS
    yield from live_run(3)
    # 1. Ctrl+Tab: the mode pie (Weight Paint is its upper left item for a mesh), then a real stroke.
    yield from _ctrl_tab_pie(-150, 150)
    check("Ctrl+Tab's pie takes the object to Weight Paint during a run", _run_goes_on(obj, 'WEIGHT_PAINT'),
          "mode %s" % obj.mode)
    op = live_operator()
    check("while painting the hints say that clicks paint", op is not None and tuple(op.key_hints()) == paint,
          str(op.key_hints()) if op else "no run")
    obj.vertex_groups.active_index = obj.vertex_groups["Paint"].index
    bpy.context.scene.tool_settings.unified_paint_settings.weight = 1.0
    for brush in bpy.data.brushes:
        if brush.use_paint_weight:
            brush.weight = 1.0
    x, y = kit.viewport_point()
    _stroke(x - 120, y, 240)
    yield 1.0
    _screenshot("weight_paint_mid_run.png", whole_window=True)
    check("a left-drag in Weight Paint paints and does not end the run", _run_goes_on(obj, 'WEIGHT_PAINT'))
    painted = np.array([g.weight for v in obj.data.vertices for g in v.groups
                        if g.group == obj.vertex_groups["Paint"].index])
    check("the stroke painted the Region", painted.max() > 0.5, "max weight %.2f" % painted.max())
    yield from _ctrl_tab_pie(-150, 0)  # Object Mode: the pie's left item
    check("Ctrl+Tab's pie takes it back to Object Mode, the run goes on", _run_goes_on(obj, 'OBJECT'),
          "mode %s" % obj.mode)
    yield 0.5
    op = live_operator()
    check("back in Object Mode the run took the stroke", op is not None and op.session.weights["Paint"].max() > 0.5)
    check("back in Object Mode the hints are the run's own", op is not None and tuple(op.key_hints())[:2] ==
          op_class.KEY_HINTS)
    # 2. The header's mode menu (the header keeps its menus during a run).
    yield from _header_mode_menu('W')
    check("the header's mode menu takes the object to Weight Paint during a run", _run_goes_on(obj, 'WEIGHT_PAINT'),
          "mode %s" % obj.mode)
    yield from _header_mode_menu('O')
    check("the header's mode menu takes it back to Object Mode", _run_goes_on(obj, 'OBJECT'), "mode %s" % obj.mode)
    # 3. The sidebar's Paint Region button, and its Back to Object Mode.
    obj.vertex_groups.active_index = 0 if obj.vertex_groups[0].name != "Paint" else len(obj.vertex_groups) - 1
    yield from _click_sidebar_button("gauss_paint_region")
    check("the sidebar's Paint Region button takes the object to Weight Paint", found["clicked"] and
          _run_goes_on(obj, 'WEIGHT_PAINT'), "found %s, mode %s" % (found["clicked"], obj.mode))
    check("Paint Region makes the Region the group painted", obj.vertex_groups.active.name == "Paint")
    yield 2.0  # the sub-panels slide to the place the longer hints leave them
    _screenshot("sidebar_paint_region.png")
    yield from _click_sidebar_button("gauss_paint_region")
    check("Back to Object Mode in the sidebar", found["clicked"] and _run_goes_on(obj, 'OBJECT'),
          "found %s, mode %s" % (found["clicked"], obj.mode))
    yield from end_with('ESC', "Esc after painting the documented ways restores the mesh", name, original)


def run_scenario(scenario_name, name, prepared):
    return globals()[scenario_name](name, prepared)


kit.start(kit.cube_style_scenarios(("paint_and_return", "the_documented_ways"), run_scenario,
                                   prepare=unpainted_region),
          "windowed_paint_strength_result.txt", time_limit=TIME_LIMIT)
