"""The live run in a real window, second part: undo, clicks, several objects, messages.
Run by run_windowed.sh after windowed_driver.py, whose helpers it uses:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_live_run.py -- BUILD_DIR

Everything is done as a person would: typing into the sidebar's Sigma field, G and a
click to move, Ctrl+Z, drags on the navigation gizmo, clicks in headers and the outliner.
The summary goes to BUILD_DIR/screenshots/windowed_live_run_result.txt.
"""

import os
import re
import sys
import tempfile
import threading
import time

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_driver as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_driver import (  # noqa: E402
    check, coords, live_operator, live_run, new_reports, press, push_undo, view3d, viewport_point,
    wait_steps, wait_stopped, window)
from scene_kit import activate  # noqa: E402
from windowed_actions import move_with_g  # noqa: E402
import helpers  # noqa: E402

SIGMA_PATH = "gauss_stylization.styles[0].sigma"
TIME_LIMIT = 900.0  # seconds: a 2-core machine busy with other builds redraws a window slowly (idle: ~2 min)
USER_UNDO_STEPS = 47  # an undo_steps value of the artist's that every ending must give back


# -- doing things as a person would -------------------------------------------------------

def _property_under_mouse(x, y):
    """Generator: the mouse to (x, y); found["path"] = the data path of the property there (or "")."""
    area, regions = view3d()
    window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.02
    bpy.context.window_manager.clipboard = ""
    try:
        with bpy.context.temp_override(window=window(), area=area, region=regions['UI']):
            bpy.ops.ui.copy_data_path_button(full_path=False)
    except RuntimeError:  # no property under the mouse
        pass
    found["path"] = bpy.context.window_manager.clipboard


def find_sidebar_field(data_path):
    """Generator: hover down the sidebar and ask Blender which property is under the mouse;
    leaves the middle of ``data_path``'s row in found["at"] (None if not found). A place found
    before is checked first (the panel's layout rarely changes)."""
    known = found.get(data_path)
    if known is not None:
        yield from _property_under_mouse(*known)
        if found["path"] == data_path:
            found["at"] = known
            return
    ui = view3d()[1]['UI']
    x = ui.x + ui.width // 2 + 20  # the value column of a property row
    row = int(18 * bpy.context.preferences.system.ui_scale)  # a little less than a row's height
    hit = None
    for y in range(ui.y + ui.height - row // 2, ui.y, -row):  # every row is hit once
        yield from _property_under_mouse(x, y)
        if found["path"] == data_path:
            hit = y
            break
    if hit is not None:  # the row's middle: the median of the points around the hit that are on it
        on_row = [hit]
        for y in range(hit - row, hit + row + 1, 3):
            yield from _property_under_mouse(x, y)
            if found["path"] == data_path:
                on_row.append(y)
        hit = sorted(on_row)[len(on_row) // 2]
    found["at"] = found[data_path] = (x, hit) if hit is not None else None


found = {}


def type_into_field(data_path, text):
    """Generator: click the sidebar field of ``data_path``, type ``text`` and press Enter."""
    yield from find_sidebar_field(data_path)
    check("the sidebar shows the field %s" % data_path, found["at"] is not None)
    if found["at"] is None:
        return
    win = window()
    x, y = found["at"]
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.1
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y)
    yield 0.1
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x, y=y)  # a click starts editing the number as text
    yield 0.2
    win.event_simulate(type='A', value='PRESS', ctrl=True)  # select what is there
    win.event_simulate(type='A', value='RELEASE', ctrl=True)
    for char in text:
        key = {"0": 'ZERO', "1": 'ONE', "2": 'TWO', "3": 'THREE', "4": 'FOUR', "5": 'FIVE', "6": 'SIX',
               "7": 'SEVEN', "8": 'EIGHT', "9": 'NINE', ".": 'PERIOD'}[char]
        win.event_simulate(type=key, value='PRESS', unicode=char)
        win.event_simulate(type=key, value='RELEASE')
    win.event_simulate(type='RET', value='PRESS')
    win.event_simulate(type='RET', value='RELEASE')
    yield 0.3


def drag(x, y, dx, dy, steps=10, **modifiers):
    """Generator: press the left button at (x, y), move by (dx, dy) in ``steps``, release."""
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.05
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y, **modifiers)
    for i in range(1, steps + 1):
        yield 0.03
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + dx * i // steps, y=y + dy * i // steps)
    yield 0.05
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x + dx, y=y + dy, **modifiers)
    yield 0.3


def key(event_type, **modifiers):
    """Generator: a key pressed over the viewport, then time for Blender to act on it."""
    press(event_type, *viewport_point(), **modifiers)
    yield 0.5


def navigation_gizmo_buttons():
    """Centres of the rotation gizmo and the zoom button as Blender 3.4 lays them out
    (view3d_gizmo_navigate.c): top right of the region's part no header or sidebar covers."""
    area, regions = view3d()
    preferences = bpy.context.preferences
    scale = preferences.system.ui_scale
    right = regions['UI'].x if area.spaces.active.show_region_ui else regions['WINDOW'].x + regions['WINDOW'].width
    top = regions['TOOL_HEADER'].y if area.spaces.active.show_region_tool_header else regions['HEADER'].y
    offset = (preferences.view.gizmo_size_navigate_v3d / 2 + 10) * scale
    rotate = (int(right - offset), int(top - offset))
    zoom = (int(right - 30 * scale * 0.75), int(top - offset * 2.1))
    return rotate, zoom


def selection_state(obj):
    return coords(obj), tuple(obj.location), obj.gauss_stylization.styles[0].sigma


# -- undo ----------------------------------------------------------------------------------

def edit_during_a_run(name, sigma, ending, states):
    """Generator: a live run in which Sigma is typed into the sidebar and the object is moved
    with G and a click, ended by the key ``ending``; states["before"] / ["after"]: the object's
    selection_state() before the run (an undo step) and after it ended."""
    obj = activate(bpy.data.objects[name])
    push_undo("Before the run")
    states["before"] = selection_state(obj)
    yield from live_run(5)
    yield from type_into_field(SIGMA_PATH, sigma)
    check("Sigma typed into the sidebar during a run reaches the run",
          live_operator() is not None and obj.gauss_stylization.styles[0].sigma == float(sigma))
    location = tuple(obj.location)
    yield from move_with_g()
    check("G and a click during a run move the object and leave the run going",
          live_operator() is not None and tuple(obj.location) != location)
    yield from wait_steps(live_operator().session.steps + 3 if live_operator() else 0)
    yield from key(ending)
    yield from wait_stopped()
    states["after"] = selection_state(bpy.data.objects[name])


def sigma_and_move_during_a_kept_run(name):
    """Sigma typed into the sidebar and a G move during a run, then Enter: one Ctrl+Z gives
    back exactly the mesh (and settings, and place) from before the run."""
    states = {}
    yield from edit_during_a_run(name, "8", 'RET', states)
    before, kept = states["before"], states["after"]
    check("Enter keeps the run (with the edits made during it)",
          live_operator() is None and not np.array_equal(kept[0], before[0]) and kept[2] == 8.0)
    yield from key('Z', ctrl=True)
    obj = bpy.data.objects[name]
    now = selection_state(obj)
    check("one Ctrl+Z after a kept run with edits gives the mesh from before the run bit-exactly",
          np.array_equal(now[0], before[0]), "max diff %.3g" % np.abs(now[0] - before[0]).max())
    check("... and the settings and place from before the run (the edits belong to the run's step)",
          now[1:] == before[1:], "now %s before %s" % (now[1:], before[1:]))
    yield from key('Z', ctrl=True, shift=True)
    obj = bpy.data.objects[name]
    check("Ctrl+Shift+Z then brings the kept result back, edits included",
          np.array_equal(coords(obj), kept[0]) and selection_state(obj)[1:] == kept[1:])
    yield from key('Z', ctrl=True)  # back to before the run for the next scenario


def sigma_and_move_during_a_cancelled_run(name):
    """The same edits, then Esc: neither redo nor undo shows a cancelled shape; the edits
    are one undo step."""
    states = {}
    yield from edit_during_a_run(name, "7", 'ESC', states)
    before, after_esc = states["before"], states["after"]
    check("Esc restores the mesh bit-exactly and keeps the edits",
          np.array_equal(after_esc[0], before[0]) and after_esc[2] == 7.0 and after_esc[1] != before[1])
    never = []
    for keys in (dict(ctrl=True, shift=True), dict(ctrl=True), dict(ctrl=True, shift=True), dict(ctrl=True)):
        yield from key('Z', **keys)
        never.append(np.array_equal(coords(bpy.data.objects[name]), before[0]))
    check("after Esc, Ctrl+Shift+Z / Ctrl+Z / Ctrl+Shift+Z / Ctrl+Z never show a cancelled shape", all(never),
          str(never))
    check("... and the edits made during the cancelled run are one undo step",
          selection_state(bpy.data.objects[name])[1:] == before[1:])
    yield from key('Z', ctrl=True, shift=True)
    check("... which redo brings back (with the original mesh)",
          selection_state(bpy.data.objects[name])[1:] == after_esc[1:]
          and np.array_equal(coords(bpy.data.objects[name]), before[0]))


# -- clicks --------------------------------------------------------------------------------

def gizmo_and_header_clicks(name):
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    region_3d = view3d()[0].spaces.active.region_3d
    # The checks below need a run that keeps stepping: at the default tolerance the accelerated
    # iteration converges (and the run stops stepping) within ~70 steps on Spot, before the last click.
    tolerance = obj.gauss_stylization.tolerance
    obj.gauss_stylization.tolerance = obj.gauss_stylization.bl_rna.properties["tolerance"].hard_min
    yield from live_run(3)
    rotate, zoom = navigation_gizmo_buttons()
    distance = region_3d.view_distance
    yield from drag(*zoom, 0, -60)
    check("a drag on the navigation gizmo's zoom button zooms", region_3d.view_distance != distance,
          "%.3f -> %.3f" % (distance, region_3d.view_distance))
    yield from kit.goes_on("... and the run goes on")
    rotation = tuple(region_3d.view_rotation)
    yield from drag(*rotate, 40, 0)
    check("a drag on the rotation gizmo turns the view", tuple(region_3d.view_rotation) != rotation)
    yield from kit.goes_on("... and the run goes on")
    area, regions = view3d()
    tool_header = regions['TOOL_HEADER']
    press('LEFTMOUSE', tool_header.x + tool_header.width // 2, tool_header.y + tool_header.height // 2)
    ui = regions['UI']
    press('LEFTMOUSE', ui.x + ui.width // 2, ui.y + 10)  # the empty foot of the sidebar
    toolbar = regions['TOOLS']
    press('LEFTMOUSE', toolbar.x + toolbar.width // 2, toolbar.y + toolbar.height - 30)  # a tool button
    yield 0.3
    yield from kit.goes_on("clicks in the tool header, the sidebar and the toolbar leave the run going")
    x, y = viewport_point()
    yield from drag(x - 150, y + 100, 80, -60)  # a box selection in the free viewport
    yield from kit.goes_on("a drag in the free viewport (box select) leaves the run going")
    yield from kit.end_with('ESC', "Esc after those clicks restores the mesh bit-exactly", name, original)
    obj.gauss_stylization.tolerance = tolerance


def outliner_selection(name, other):
    """Selecting another object in the outliner does not end the run (its objects are fixed)."""
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    yield from live_run(3)
    outliner = next(a for a in window().screen.areas if a.type == 'OUTLINER')
    region = next(r for r in outliner.regions if r.type == 'WINDOW')
    row = 20 * bpy.context.preferences.system.ui_scale
    x = region.x + region.width // 2
    for i in range(1, 10):  # click rows from the top until the other object is the active one
        press('LEFTMOUSE', x, int(region.y + region.height - row * (i + 0.5)))
        yield 0.2
        if bpy.context.view_layer.objects.active == bpy.data.objects[other]:
            break
    check("a click in the outliner selects another object",
          bpy.context.view_layer.objects.active == bpy.data.objects[other])
    yield from kit.goes_on("... and the run goes on")
    op = live_operator()
    check("... on the object it started with", op is not None and [s.obj.name for s in op.sessions] == [name])
    activate(bpy.data.objects[name])
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)


# -- several objects -----------------------------------------------------------------------

def several_objects(name, other):
    first, second = bpy.data.objects[name], bpy.data.objects[other]
    activate(first)
    second.select_set(True)
    originals = coords(first), coords(second)
    yield from live_run(4)
    op = live_operator()
    check("a live run with two selected meshes stylizes both",
          op is not None and sorted(s.obj.name for s in op.sessions) == sorted([name, other]))
    yield from wait_steps(8)
    moved = [not np.array_equal(coords(o), start) for o, start in zip((first, second), originals)]
    check("... both move", all(moved), str(moved))
    yield from key('ESC')
    yield from wait_stopped()
    check("Esc restores both meshes bit-exactly", all(
        np.array_equal(coords(bpy.data.objects[n]), start) for n, start in zip((name, other), originals)))
    push_undo("Before the two-object run")
    yield from live_run(6)
    yield from key('RET')
    yield from wait_stopped()
    kept = [not np.array_equal(coords(bpy.data.objects[n]), s) for n, s in zip((name, other), originals)]
    yield from key('Z', ctrl=True)
    check("Enter keeps both, and one Ctrl+Z gives both back bit-exactly", all(kept) and all(
        np.array_equal(coords(bpy.data.objects[n]), start) for n, start in zip((name, other), originals)))
    activate(bpy.data.objects[name])


# -- messages ------------------------------------------------------------------------------

def region_group_deleted(name):
    obj = bpy.data.objects[name]
    activate(obj)
    original = coords(obj)
    group = obj.vertex_groups.new(name="Top")
    group.add([i for i, co in enumerate(original) if co[2] > original[:, 2].mean()], 1.0, 'REPLACE')
    obj.gauss_stylization.styles[0].vertex_group = "Top"
    new_reports()
    yield from live_run(3)
    obj.vertex_groups.active_index = group.index
    area, regions = view3d()
    with bpy.context.temp_override(window=window(), area=area, region=regions['WINDOW'], object=obj):
        bpy.ops.object.vertex_group_remove()  # the minus button of the Vertex Groups panel
    yield 0.3
    text = new_reports()
    check("deleting the Region's group during a run says so at once",
          "'Top' was deleted while Stylize was running" in text, repr(text[-300:]))
    op = live_operator()
    steps = op.session.steps if op else None
    yield 0.5
    check("... and pauses the run", op is not None and live_operator() is op and op.session.steps == steps)
    obj.gauss_stylization.styles[0].vertex_group = ""
    yield from kit.goes_on("picking no group resumes it")
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)


# -- converged: stop when converged --------------------------------------------------------

def converged_then_sigma_resumes(name):
    """A live run whose object reaches its Tolerance stops stepping and says Converged; a Sigma typed
    into the sidebar makes it step again; Esc restores the mesh."""
    obj = bpy.data.objects[name]
    activate(obj)
    settings = obj.gauss_stylization
    original, before = coords(obj), (settings.tolerance, settings.styles[0].sigma)
    settings.tolerance = 0.05  # converges within a few dozen steps
    yield from live_run(1)
    op = live_operator()
    deadline = time.monotonic() + 30.0
    while op is not None and not op.live.converged and time.monotonic() < deadline:
        yield 0.1
    check("a live run that converged says so (status bar and panel)",
          op is not None and "Converged" in op.live.status_text() and op.live.panel_title() == "Converged",
          op.live.status_text() if op else "no run")
    steps = op.session.steps if op else None
    yield 0.5
    check("... and stops stepping", op is not None and live_operator() is op and op.session.steps == steps,
          "steps %s -> %s" % (steps, op.session.steps if op else None))
    yield from type_into_field(SIGMA_PATH, "11")
    deadline = time.monotonic() + 10.0
    while op is not None and op.session.steps == steps and time.monotonic() < deadline:
        yield 0.05
    check("a Sigma typed into the sidebar makes it step again",
          op is not None and live_operator() is op and op.session.steps > steps
          and op.session.applied["styles"][0]["sigma"] == 11.0)
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)
    settings.tolerance, settings.styles[0].sigma = before


def cubic_converges_accelerated(name):
    """The cubic method in a live run reaches the default Tolerance and says Converged, in fewer
    than half the steps of the plain iteration on the same mesh and settings (the acceleration
    serves the cubic method too); Esc restores the mesh."""
    obj = bpy.data.objects[name]
    activate(obj)
    settings = obj.gauss_stylization
    original, before = coords(obj), settings.method
    settings.method = 'CUBIC'
    yield from live_run(1)
    op = live_operator()
    deadline = time.monotonic() + 120.0
    while op is not None and not op.live.converged and time.monotonic() < deadline:
        yield 0.1
    steps = op.session.steps if op else None
    check("a cubic live run converges and says so",
          op is not None and op.live.converged and "Converged" in op.live.status_text(),
          op.live.status_text() if op else "no run")
    # The plain iteration from the same start, on the triangles the solver sees.
    core = addon().native.core()
    plain = core.Solver(original.reshape(-1, 3).astype(np.float64), helpers.triangles(obj)[0],
                        method="cubic", acceleration=False)
    plain.cubic_lambda = settings.cubic_lambda
    plain.set_styles([core.Style.preset("cube")])
    plain_steps = plain.step_until(settings.tolerance, 2000)
    check("... in fewer than half the plain iteration's steps",
          steps is not None and plain.converged and steps < 0.5 * plain_steps,
          "live %s, plain %s" % (steps, plain_steps))
    print("cubic live run converged in %s steps, plain %s" % (steps, plain_steps), flush=True)
    yield from kit.end_with('ESC', "Esc then restores the mesh bit-exactly", name, original)
    settings.method = before


# -- a big set-up: progress while it sets up -----------------------------------------------

def big_set_up_esc(name):
    """A 360K-vertex mesh: the set-up shows its progress, Blender stays responsive, Esc cancels
    it at once and nothing has changed."""
    if not hasattr(addon().native.core(), "Progress"):  # a module whose set-ups report and cancel
        print("big_set_up_esc: skipped, this gauss_core has no Progress", flush=True)
        return
    import bmesh
    bm = bmesh.new()
    bmesh.ops.create_grid(bm, x_segments=600, y_segments=600, size=2.0)
    mesh = bpy.data.meshes.new("Big")
    bm.to_mesh(mesh)
    bm.free()
    big = bpy.data.objects.new("Big", mesh)
    big.display_type = 'BOUNDS'  # drawing 360K faces in software would be what keeps the window busy
    big.location.x = -3.0
    bpy.context.scene.collection.objects.link(big)
    activate(big)
    original, undo_steps = coords(big), _undo_steps()
    # A fast machine finishes the real set-up before the driver gets to press Esc, so each set-up
    # task is held after its real work until it is cancelled: Esc always meets it preparing.
    solver_setup, core = addon().run.solver_setup, addon().native.core()
    real_init = solver_setup.BackgroundSetup.__init__

    def held(run):
        def run_then_hold(progress):
            result, began = run(progress), time.monotonic()
            while not progress.cancelled and time.monotonic() - began < 60.0:
                time.sleep(0.01)
            if progress.cancelled:
                raise core.Cancelled("cancelled while held")
            return result
        return run_then_hold

    solver_setup.BackgroundSetup.__init__ = lambda setup, gauss_core, tasks: real_init(
        setup, gauss_core, [(weight, text, held(run)) for weight, text, run in tasks])
    try:
        yield from _big_set_up_esc_checks(big, original, undo_steps)
    finally:
        solver_setup.BackgroundSetup.__init__ = real_init
    bpy.data.objects.remove(bpy.data.objects["Big"])
    bpy.data.meshes.remove(mesh)
    activate(bpy.data.objects[name])


def _big_set_up_esc_checks(big, original, undo_steps):
    kit.start_live_run()
    yield 1.0
    op = live_operator()
    check("a big mesh is prepared before it runs", op is not None and op.preparing,
          "preparing %s" % (op.preparing if op else None))
    area = view3d()[0]
    path = os.path.join(kit.SHOTS, "preparing.png")
    with bpy.context.temp_override(window=window(), area=area):
        bpy.ops.screen.screenshot(filepath=path)  # the status bar says "Preparing ... %"
    text = op.live.status_text() if op is not None else ""
    check("the status bar says how far the set-up is", re.search(r"Preparing [\d,]+ vertices\.\.\. \d+%", text),
          repr(text))
    seen, began = [], time.monotonic()  # what the driver (Python on Blender's main thread) sees meanwhile
    while (time.monotonic() - began < 8.0 and len(set(seen)) < 2 and live_operator() is not None
           and live_operator().preparing):
        seen.append(live_operator().live.setup.fraction)
        yield 0.05
    check("Blender stays responsive while it prepares (the main thread runs between the set-up's steps)",
          len(set(seen)) >= 2 and seen == sorted(seen), "fractions seen: %s" % seen)
    op = live_operator()
    check("... and is still preparing when Esc is pressed", op is not None and op.preparing)
    asked = time.monotonic()
    press('ESC', *viewport_point())
    yield from wait_stopped()
    check("Esc during the set-up ends the run at once", live_operator() is None and time.monotonic() - asked < 5.0,
          "%.1f s" % (time.monotonic() - asked))
    state = (np.array_equal(coords(bpy.data.objects["Big"]), original), _undo_steps() == undo_steps,
             not [t for t in threading.enumerate() if t.name == "Gauss Stylize set-up"],
             len(bpy.data.objects["Big"].gauss_stylization.styles) == 0)
    check("... leaving nothing changed and nothing running (mesh, undo steps, no thread, no style added)",
          all(state), str(state))


def scripted_run_in_a_window(name):
    """A run that holds the window (a script, the redo panel) shows Blender's progress indicator
    (on the mouse cursor) and sets the status text; afterwards both are gone."""
    progress = addon().run.progress
    shown = []
    real_update = progress.ProgressReport.update

    def update(report, fraction, text):
        real_update(report, fraction, text)
        shown.append((report.shown, report.workspace is not None, fraction))

    progress.ProgressReport.update = update
    saved, progress.SHOW_AFTER = progress.SHOW_AFTER, 0.0  # every run counts as long here
    try:
        activate(bpy.data.objects[name])
        original = coords(bpy.data.objects[name])
        with kit.override():
            result = bpy.ops.object.gauss_stylize('EXEC_DEFAULT', True, iterations=30)
    finally:
        progress.SHOW_AFTER = saved
        progress.ProgressReport.update = real_update
    yield 0.3
    check("a scripted run in the window shows its progress (indicator and status text)",
          result == {'FINISHED'} and shown and all(s[0] and s[1] for s in shown) and shown[-1][2] == 1.0
          and not np.array_equal(coords(bpy.data.objects[name]), original), str(shown[-3:]))
    yield from key('Z', ctrl=True)
    check("... and is one undo step", np.array_equal(coords(bpy.data.objects[name]), original))


# -- undo steps given back on every ending -------------------------------------------------

def addon():
    import gauss_stylization  # windowed_driver put BUILD/addon on sys.path
    return gauss_stylization


def _undo_steps():
    return bpy.context.preferences.edit.undo_steps


def _raise_in_tick(*_args):
    raise ZeroDivisionError("a failure injected into the tick")


def _edit_menu_undo():
    with kit.override():
        bpy.ops.ed.undo()  # what Edit > Undo runs


def _addon_disabled():
    addon().unregister()
    addon().register()


def undo_steps_given_back(name):
    preferences = bpy.context.preferences
    preferences.edit.undo_steps = USER_UNDO_STEPS
    preferences.is_dirty = False
    endings = [
        ("Enter", lambda: press('RET', *viewport_point())),
        ("a plain click", lambda: press('LEFTMOUSE', *viewport_point())),
        ("Esc", lambda: press('ESC', *viewport_point())),
        ("a right-click", lambda: press('RIGHTMOUSE', *viewport_point())),
        ("Edit > Undo", _edit_menu_undo),
        ("the add-on disabled", _addon_disabled),
        ("an error in a tick", lambda: setattr(live_operator().live, "tick", _raise_in_tick)),  # last: a popup
    ]
    for label, end in endings:
        activate(bpy.data.objects[name])
        yield from live_run(2)
        during = _undo_steps()
        end()
        yield from wait_stopped()
        yield 0.2
        check("undo is off during a run and given back after %s" % label,
              during == 0 and _undo_steps() == USER_UNDO_STEPS and not preferences.is_dirty
              and live_operator() is None, "during %s, after %s, dirty %s" % (during, _undo_steps(),
                                                                           preferences.is_dirty))
    press('ESC', *viewport_point())  # close the error report's popup, which takes the keys
    yield 0.3
    yield from window_closed_mid_run(name)


def window_closed_mid_run(name):
    """Blender cancels the modal operator when its window closes."""
    activate(bpy.data.objects[name])
    original = coords(bpy.data.objects[name])
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.window_new()
    yield 0.5
    new_window = bpy.context.window_manager.windows[-1]
    area = next(a for a in new_window.screen.areas if a.type == 'VIEW_3D')
    region = next(r for r in area.regions if r.type == 'WINDOW')
    with bpy.context.temp_override(window=new_window, area=area, region=region):
        bpy.ops.object.gauss_stylize('INVOKE_DEFAULT')
    yield from wait_steps(3)
    with bpy.context.temp_override(window=new_window):
        bpy.ops.wm.window_close()
    yield from wait_stopped()
    yield 0.3
    check("closing the run's window ends it, restores the mesh and gives undo back",
          live_operator() is None and _undo_steps() == USER_UNDO_STEPS
          and np.array_equal(coords(bpy.data.objects[name]), original))


def file_loaded_mid_run(name):
    path = os.path.join(tempfile.mkdtemp(prefix="gauss_live_run_"), "scene.blend")
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.save_as_mainfile(filepath=path)
    activate(bpy.data.objects[name])
    yield from live_run(2)
    with bpy.context.temp_override(window=window()):
        bpy.ops.wm.open_mainfile(filepath=path)
    yield 0.5
    check("opening a file during a run gives undo back", live_operator() is None and
          _undo_steps() == USER_UNDO_STEPS)
    os.remove(path)


# -- scenario -------------------------------------------------------------------------------

def make_other(name):
    """A second mesh beside the first (its own copy of the mesh)."""
    source = bpy.data.objects[name]
    other = source.copy()
    other.data = source.data.copy()
    other.name = "Other"
    other.location = (source.dimensions.x * 1.5, 0.0, 0.0)
    bpy.context.scene.collection.objects.link(other)
    activate(source)
    push_undo("Second object")
    return other.name


SCENARIOS = ("sigma_and_move_during_a_kept_run", "sigma_and_move_during_a_cancelled_run",
             "gizmo_and_header_clicks", "outliner_selection", "several_objects", "region_group_deleted",
             "converged_then_sigma_resumes", "cubic_converges_accelerated", "big_set_up_esc", "scripted_run_in_a_window", "undo_steps_given_back",
             "file_loaded_mid_run")  # the last replaces the whole file


def scenario():
    started = time.monotonic()
    name = kit.set_up()
    yield 1.0
    yield from kit.open_gauss_tab()
    addon().settings_io.add_slot(bpy.data.objects[name].gauss_stylization, {"preset": 'CUBE'})
    push_undo("Cube style")
    other = make_other(name)
    # GAUSS_WINDOWED_ONLY=name,name runs only those scenarios (while working on one).
    only = [n for n in os.environ.get("GAUSS_WINDOWED_ONLY", "").split(",") if n]
    for scenario_name in SCENARIOS:
        if only and scenario_name not in only:
            continue
        print("-- %s (%.0f s)" % (scenario_name, time.monotonic() - started), flush=True)
        function = globals()[scenario_name]
        arguments = (name, other) if function.__code__.co_argcount == 2 else (name,)
        yield from function(*arguments)


kit.start(scenario(), "windowed_live_run_result.txt", time_limit=TIME_LIMIT)
