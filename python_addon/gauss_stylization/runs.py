"""The live runs: which objects are being stylized, and ending them all.

Module state, because modal operators live outside RNA. A run is the modal
operator itself (operators.OBJECT_OT_gauss_stylize); all this module asks of
it is ``stop(context, keep=False)`` and ``report(...)``.
"""

import bpy

# Object pointer -> its live run, so a second Stylize or a Reset cannot interfere with it.
running = {}


def start(obj, run):
    running[obj.as_pointer()] = run


def is_running(obj):
    return obj.as_pointer() in running


def forget(run):
    for key, value in list(running.items()):
        if value is run:
            del running[key]


def stop_all(context, report=None):
    """Restore and end every live run (add-on disabled, undo/redo mid-run)."""
    for run in list(running.values()):
        run.stop(context, keep=False)
        if report:
            run.report({'WARNING'}, report)


@bpy.app.handlers.persistent
def _end_runs_before_undo(*_args):
    # Ctrl+Z is swallowed during a run, but the Edit menu (or F9 redo) still
    # reaches undo. Memory undo keeps a mesh it thinks unchanged as it is in
    # memory, so the half-done result would stay, in no undo step, and the run
    # would stop without restoring. Restoring first makes memory match the undo
    # step again.
    stop_all(bpy.context, report="Stylize cancelled by undo/redo; the mesh was restored first")


UNDO_HANDLER_LISTS = ("undo_pre", "redo_pre")


def register_handlers():
    for name in UNDO_HANDLER_LISTS:
        handlers = getattr(bpy.app.handlers, name)
        if _end_runs_before_undo not in handlers:
            handlers.append(_end_runs_before_undo)


def unregister_handlers():
    for name in UNDO_HANDLER_LISTS:
        handlers = getattr(bpy.app.handlers, name)
        if _end_runs_before_undo in handlers:
            handlers.remove(_end_runs_before_undo)
