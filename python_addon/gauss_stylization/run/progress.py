"""Progress of a job that may take a while: Blender's progress indicator, a status-bar text
and, in background mode, a line on stdout.

    report = ProgressReport(context, "Gauss Stylize")
    report.update(0.4, "Preparing 501,128 vertices")  # -> "Preparing 501,128 vertices... 40%"
    report.end()                                       # or: with ProgressReport(...) as report:

Nothing shows for a job that is over within SHOW_AFTER seconds: the indicator would only
flicker. After that the window manager's progress indicator (0 to 100) and the status bar
show it; in background mode (``blender -b``) a line is printed whenever the job passes a
tenth, so a log shows progress at least every 10% (when the job reports that often). A job
in stages (set-up, then steps) starts each stage's fraction at 0 again. Meant for every long job of the add-on:
set-ups and scripted runs here, bakes elsewhere.
"""

import math
import time

import bpy

SHOW_AFTER = 0.5  # seconds before anything is shown


def progress_text(text, fraction=None):
    """"Preparing 501,128 vertices... 40%" (fraction 0..1, None when unknown)."""
    if fraction is None:
        return text + "..."
    return "%s... %d%%" % (text, int(100.0 * min(max(fraction, 0.0), 1.0)))


def short_number(value):
    """3.1e-3 rather than 3.1e-03: short enough for the sidebar."""
    mantissa, exponent = ("%.1e" % value).split("e")
    return "%se%d" % (mantissa, int(exponent))


SETTLED_BEFORE = 0.99  # the most "settling" says: 100% is for "converged" alone


def settling_fraction(change, tolerance):
    """How far a run has settled, 0..SETTLED_BEFORE, from its last step's relative change (reldV) on a
    log scale: 0 at a change of 1 (a first step: as long as the whole way so far), 1 at the Tolerance,
    each tenfold drop in change the same stretch. None before the first step and after a setting changed
    (an infinite change)."""
    if not math.isfinite(change):
        return None
    if not 0.0 < tolerance < 1.0:  # nothing to measure against
        return 0.0
    if change <= 0.0:
        return SETTLED_BEFORE
    fraction = math.log(change) / math.log(tolerance)
    return min(max(fraction, 0.0), SETTLED_BEFORE)


def settling_text(fraction):
    """"settling, 80%" (an artist's words for settling_fraction()'s number)."""
    return "settling, %d%%" % int(100.0 * fraction)


def settling_details(change, tolerance):
    """The numbers behind "settling": the tooltip of the sidebar's progress row."""
    return ("The last step changed the mesh by %s of its change so far; it converges (and stops) below %s "
            "(Tolerance)" % (short_number(change), short_number(tolerance)))


class ProgressReport:
    """title: what the job is, leads every status text and printed line.
    status:   show the text in the status bar (False when the caller writes the status itself).

    A job that holds the interface (an operator's execute: a script, the redo panel) shows
    the progress indicator on the mouse cursor, which needs no redraw; its status text only
    appears when the window is drawn again. (Forcing a redraw from inside an operator with
    wm.redraw_timer crashed Blender 3.4 under test, so it is not done.)"""

    def __init__(self, context, title, status=True):
        self.title = title
        self.window_manager = context.window_manager
        self.workspace = context.workspace if status else None
        self.background = bpy.app.background
        self.started = time.monotonic()
        self.shown = False
        self.printed_tenth = -1
        self.text = ""

    def __enter__(self):
        return self

    def __exit__(self, *_exc):
        self.end()

    @property
    def seconds(self):
        return time.monotonic() - self.started

    def update(self, fraction, text):
        """fraction: 0..1 of the whole job, or None when unknown; text: what it does now."""
        self.text = progress_text(text, fraction)
        if not self.shown:
            if self.seconds < SHOW_AFTER:
                return
            self.shown = True
            if not self.background:
                self.window_manager.progress_begin(0, 100)
        if self.background:
            tenth = 0 if fraction is None else int(10.0 * min(max(fraction, 0.0), 1.0))
            if tenth < self.printed_tenth:  # the fraction went back: the job's next stage began
                self.printed_tenth = -1
            if tenth > self.printed_tenth:
                self.printed_tenth = tenth
                print("%s: %s" % (self.title, self.text), flush=True)
            return
        self.window_manager.progress_update(0 if fraction is None else 100.0 * fraction)
        if self.workspace is not None:
            self.workspace.status_text_set("%s: %s" % (self.title, self.text))

    def end(self):
        """Take the indicator and text away (safe to call more than once)."""
        if not self.shown:
            return
        self.shown = False
        if self.background:
            print("%s: done in %.1f s" % (self.title, self.seconds), flush=True)
            return
        self.window_manager.progress_end()
        if self.workspace is not None:
            self.workspace.status_text_set(None)
