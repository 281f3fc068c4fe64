"""The live runs: which objects are being stylized, and ending them all.

Module state, because modal operators live outside RNA. A run is the modal
operator itself (operators.OBJECT_OT_gauss_stylize); all this module asks of
it is ``stop(context, keep=False)``, ``report(...)`` and ``sessions``.

Undo is suspended while any run is live (undo_guard): from the moment the first
run registers until the last one is forgotten. Every way a run ends goes
through forget(): Enter, clicks, Esc, an error in a tick, Blender cancelling the
modal operator (window closed, file loaded, quitting), and the handlers below
(undo/redo, file loading) or unregister() ending all runs.
"""

import bpy

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


@bpy.app.handlers.persistent
def _end_runs_before_undo(*_args):
    # Ctrl+Z is swallowed during a run, but the Edit menu (or F9 redo) still
    # reaches undo. Memory undo keeps a mesh it thinks unchanged as it is in
    # memory, so the half-done result would stay, in no undo step, and the run
    # would stop without restoring. Restoring first makes memory match the undo
    # step again (and gives undo its steps back before it looks at them).
    stop_all(bpy.context, report="Stylize cancelled by undo/redo; the mesh was restored first")


@bpy.app.handlers.persistent
def _end_runs_before_load(*_args):
    # Blender also cancels the modal operator when a file loads; ending the runs
    # here first makes sure the preferences are whole before anything else runs.
    stop_all(bpy.context)


HANDLERS = (("undo_pre", _end_runs_before_undo), ("redo_pre", _end_runs_before_undo),
            ("load_pre", _end_runs_before_load))


def register_handlers():
    for name, handler in HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        if handler not in handlers:
            handlers.append(handler)


def unregister_handlers():
    for name, handler in HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        if handler in handlers:
            handlers.remove(handler)
