"""Quitting Blender during a live run must not save the preferences with undo off.

A live run sets Preferences > Editing > Undo Steps to 0 while it runs, and Blender
saves the preferences when it quits (if they are marked changed and auto-save is
on, the default). run_windowed.sh runs this file three times with the same
BLENDER_USER_CONFIG folder:

    blender -b --factory-startup -P windowed_quit.py -- BUILD save    # the artist's preferences
    blender --enable-event-simulate -P windowed_quit.py -- BUILD quit  # a run, then quit (window)
    blender -b -P windowed_quit.py -- BUILD check                     # what was saved

The last prints "N passed, M failed" and exits non-zero on a failure.
"""

import os
import sys

import bpy

ARGV = sys.argv[sys.argv.index("--") + 1:]
BUILD, MODE = os.path.abspath(ARGV[0]), ARGV[1]
USER_UNDO_STEPS = 41
RESULT = os.path.join(os.environ["BLENDER_USER_CONFIG"], "quit_mid_run.txt")


def save():
    preferences = bpy.context.preferences
    preferences.edit.undo_steps = USER_UNDO_STEPS
    preferences.use_preferences_save = True      # Blender's default: save changed preferences on quit
    preferences.view.show_splash = False
    preferences.view.use_save_prompt = False     # quit at once although the scene changed
    bpy.ops.wm.save_userpref()


def quit_mid_run():
    sys.path.insert(0, os.path.join(BUILD, "addon"))
    import gauss_stylization
    gauss_stylization.register()
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=4)
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == 'VIEW_3D')
    region = next(r for r in area.regions if r.type == 'WINDOW')
    state = {"ticks": 0}

    def step():
        runs = gauss_stylization.run.runs.live_runs()
        if state["ticks"] == 0:
            with bpy.context.temp_override(window=window, area=area, region=region):
                bpy.ops.object.gauss_stylize('INVOKE_DEFAULT')
        elif runs and runs[0].session is not None and runs[0].session.steps >= 3:
            with open(RESULT, "w") as handle:
                handle.write("undo_steps during the run: %d\n" % bpy.context.preferences.edit.undo_steps)
            with bpy.context.temp_override(window=window):
                bpy.ops.wm.quit_blender()  # what File > Quit and closing the window do
            return None
        state["ticks"] += 1
        return 0.1 if state["ticks"] < 300 else None

    bpy.app.timers.register(step, first_interval=1.0)


def check():
    results = []
    during = open(RESULT).read().strip() if os.path.exists(RESULT) else "no run"
    results.append(("undo was off during the run", during == "undo_steps during the run: 0", during))
    saved = bpy.context.preferences.edit.undo_steps
    results.append(("quitting during a run keeps the artist's undo steps in the saved preferences",
                    saved == USER_UNDO_STEPS, "saved %d" % saved))
    for name, passed, detail in results:
        print("%s: %s %s" % ("PASS" if passed else "FAIL", name, detail))
    failed = sum(1 for _, passed, _ in results if not passed)
    print("quit: %d passed, %d failed" % (len(results) - failed, failed), flush=True)
    sys.exit(1 if failed else 0)


{"save": save, "quit": quit_mid_run, "check": check}[MODE]()
