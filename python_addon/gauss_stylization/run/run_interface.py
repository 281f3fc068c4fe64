"""What a live run is, written once: the interface runs.py, ui.py, modal_events.py and the handle tool
ask of it. Two operators implement it, the live Stylize (operators.OBJECT_OT_gauss_stylize) and the
bakes (bake/bake_operators.py); tests/blender/test_run_interface.py checks both against these classes.
"""

from typing import Protocol


class Run(Protocol):
    """Any live run: a modal operator registered with runs.start() until runs.forget()."""

    @property
    def sessions(self):
        """The session.Session of each object being stylized live (a bake: none)."""

    def stop(self, context, keep):
        """End the run at once: keep its results or restore (undo, a file loaded, the add-on disabled).
        Runs once; later calls do nothing."""

    def cancel_keeping_edits(self, context):
        """End the run as Esc does: restore, and keep what was edited meanwhile as one undo step.
        True if that step was pushed."""

    def hold_for_save(self, context):
        """Just before a file is written: show what Esc would leave."""

    def resume_after_save(self, context):
        """After the file was written: the run's state back."""

    def report(self, type, message):
        """bpy.types.Operator.report: a message in the status bar and the Info log."""

    def panel_state(self):
        """(title, [(text, icon)], key hints) for the sidebar's box while the run goes on (ui.py)."""


class StylizeRun(Run, Protocol):
    """A live Stylize besides: what modal_events.py's handlers and the handle tool ask of it. Its
    invoke() also gives it ``live`` (a live_run.LiveRun), ``scratch`` (handlers' state by name) and
    ``notes`` (texts the status bar shows after the run's own, by name)."""

    @property
    def preparing(self):
        """True while the solvers are still being set up."""

    def end(self, context, keep, why=None):
        """End the run from an event: keep or restore every object; returns what modal() returns."""

    def show_status(self, context, clear=False):
        """Write the header and status bar (after a handler changed notes); clear: take them away."""
