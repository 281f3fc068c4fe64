"""The live run in a real window, third part: how runs end and what they give back. Run by
run_windowed.sh after windowed_live_run.py, with windowed_kit.py's helpers:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_run_endings.py -- BUILD_DIR

  - Esc during a big mesh's set-up: the set-up shows its progress, Blender stays responsive, nothing
    has changed afterwards.
  - A run that holds the window (a script, the redo panel) shows Blender's progress indicator.
  - Undo is off during a run and the artist's undo steps come back after every ending: Enter, a click,
    Esc, a right-click, Edit > Undo, the add-on disabled, an error in a tick, the run's window closed,
    a file opened.

GAUSS_WINDOWED_ONLY=name,name runs only those scenarios. The summary goes to
BUILD_DIR/screenshots/windowed_run_endings_result.txt.
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
import windowed_kit as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_kit import (  # noqa: E402
    addon, check, coords, live_operator, live_run, press, view3d, viewport_point, wait_steps, wait_stopped, window)
from scene_kit import activate  # noqa: E402
from windowed_actions import key  # noqa: E402

TIME_LIMIT = 900.0  # seconds: a 2-core machine busy with other builds redraws a window slowly (idle: ~1 min)
USER_UNDO_STEPS = 47  # an undo_steps value of the artist's that every ending must give back


# -- a big set-up: progress while it sets up -----------------------------------------------

def big_set_up_esc(name):
    """A 360K-vertex mesh: the set-up shows its progress, Blender stays responsive, Esc cancels
    it at once and nothing has changed."""
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
    # What the driver (Python on Blender's main thread) sees while the set-up runs, from its start: a
    # set-up of about a second, so the window's screenshot and status checks come after this (a
    # software-GL screenshot alone can outlast the set-up's real work, which is then held at 100%).
    seen, began = [], time.monotonic()
    while time.monotonic() - began < 8.0 and len(set(seen)) < 2:
        op = live_operator()
        if op is not None and op.preparing:
            seen.append(op.live.setup.fraction)
        elif seen:  # it stopped preparing
            break
        yield 0.05
    check("Blender stays responsive while it prepares (the main thread runs between the set-up's steps)",
          len(set(seen)) >= 2 and seen == sorted(seen), "fractions seen: %s" % seen)
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

SCENARIOS = ("big_set_up_esc", "scripted_run_in_a_window", "undo_steps_given_back",
             "file_loaded_mid_run")  # the last replaces the whole file


def run_scenario(scenario_name, name, _prepared):
    return globals()[scenario_name](name)


kit.start(kit.cube_style_scenarios(SCENARIOS, run_scenario), "windowed_run_endings_result.txt",
          time_limit=TIME_LIMIT)
