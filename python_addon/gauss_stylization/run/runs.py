"""The live runs: which objects are being stylized, and ending them all.

Module state, because modal operators live outside RNA. A run is the modal
operator itself (operators.OBJECT_OT_gauss_stylize, or a bake); all this module asks of
it is ``stop(context, keep=False)``, ``cancel_keeping_edits(context)`` (Esc's ending),
``hold_for_save(context)`` / ``resume_after_save(context)`` around a file being written,
``report(...)`` and ``sessions``.

Undo is suspended while any run is live (undo_guard): from the moment the first
run registers until the last one is forgotten. Every way a run ends goes
through forget(): Enter, clicks, Esc, an error in a tick, Blender cancelling the
modal operator (window closed, file loaded, quitting), and the handlers below
(undo/redo, file loading) or unregister() ending all runs. A file saved during a run
holds what Esc would leave, while the run goes on.
"""

import bpy

from .. import app_handlers
from . import undo_guard

# Object pointer -> its live run, so a second Stylize or a Reset cannot interfere with it.
running = {}


def start(objects, run):
    """Register ``run`` as the live run of ``objects`` (a run fixes its objects when it starts)."""
    for obj in objects:
        running[obj.as_pointer()] = run
    undo_guard.suspend()


def is_running(obj):
    return obj.as_pointer() in running


def run_of(obj):
    """The live run stylizing ``obj``, or None."""
    return running.get(obj.as_pointer())


def live_runs():
    """Every live run, once each, in the order they started."""
    return list(dict.fromkeys(running.values()))


def session_of(obj):
    """The session.Session stylizing ``obj`` in a live run; None if there is none (or its
    solver is still being set up)."""
    run = run_of(obj)
    if run is None:
        return None
    return next((session for session in run.sessions if session.obj == obj), None)


def live_sessions():
    """The sessions of every live run (one per object being stylized)."""
    return [session for run in live_runs() for session in run.sessions]


def forget(run):
    for key, value in list(running.items()):
        if value is run:
            del running[key]
    if not running:
        undo_guard.resume()


def stop_all(context, report=None):
    """Restore and end every live run (add-on disabled, undo/redo mid-run, a file loaded)."""
    try:
        for run in live_runs():
            run.stop(context, keep=False)
            if report:
                run.report({'WARNING'}, report)
    finally:
        running.clear()
        undo_guard.resume()


# Undo (or Ctrl+Shift+Z, modal_events) during a run: the run's changes are the latest, so it takes
# back the run, as Esc does, and goes no further.
UNDO_CANCELLED = "Stylize cancelled by %s: the meshes are as before the run (nothing else was undone)"
REDO_REPORT = "Stylize cancelled by redo: the meshes were restored before redoing"
CANCELLED_UNDO_NAME = "Stylize cancelled"  # the step an undo during a run takes back instead of the artist's


def _cancel_all_keeping_edits(context, report):
    """End every run as Esc does (meshes restored, edits kept as one undo step)."""
    try:
        for run in live_runs():
            run.cancel_keeping_edits(context)
            run.report({'WARNING'}, report)
    finally:
        running.clear()
        undo_guard.resume()


@bpy.app.handlers.persistent
def _end_runs_before_undo(*_args):
    # Ctrl+Z is the run's own key (modal_events), but Edit > Undo, the Undo History and
    # F9 still reach undo. Restoring first makes memory match the undo steps again (memory undo
    # keeps a mesh it thinks unchanged as it is in memory, so the half-done result would stay,
    # in no undo step) and gives undo its steps back before it looks at them.
    if not running:
        return
    _cancel_all_keeping_edits(bpy.context, UNDO_CANCELLED % "undo")
    # An undo during a run means "not this run", as Ctrl+Z does: the undo that follows must land
    # where Esc leaves the artist (edits kept), so it is given a step of that same state to take
    # back. A jump back in the Undo History still reaches the step picked (it lies before this one).
    if bpy.ops.ed.undo_push.poll():  # (no undo stack without a window)
        bpy.ops.ed.undo_push(message=CANCELLED_UNDO_NAME)


@bpy.app.handlers.persistent
def _end_runs_before_redo(*_args):
    # Only Edit > Redo and the Undo History reach redo (Ctrl+Shift+Z is the run's key). Nothing is
    # pushed here: a push would drop the redo steps, one of which the Undo History may be loading.
    stop_all(bpy.context, report=REDO_REPORT)


@bpy.app.handlers.persistent
def _hold_runs_before_save(*_args):
    # Ctrl+S (or Save As) during a run: the file gets the meshes as Esc would leave them. (Blender's
    # auto-save waits while a modal operator runs, and then writes the last undo step, which a run
    # never adds to.)
    for run in live_runs():
        run.hold_for_save(bpy.context)


@bpy.app.handlers.persistent
def _resume_runs_after_save(*_args):
    for run in live_runs():
        run.resume_after_save(bpy.context)


@bpy.app.handlers.persistent
def _end_runs_before_load(*_args):
    # Blender also cancels the modal operator when a file loads; ending the runs
    # here first makes sure the preferences are whole before anything else runs.
    stop_all(bpy.context)


HANDLERS = (("undo_pre", _end_runs_before_undo), ("redo_pre", _end_runs_before_redo),
            ("load_pre", _end_runs_before_load), ("save_pre", _hold_runs_before_save),
            ("save_post", _resume_runs_after_save))


def register_handlers():
    app_handlers.add(HANDLERS)


def unregister_handlers():
    app_handlers.remove(HANDLERS)
