"""Progress of a bake: Blender's progress indicator and a status-bar text in a window, a printed
line at least every 10% in background mode.

One small class, so that the add-on's shared progress helper (being built with the multi-object
live run) can replace it in one place.
"""

import sys

import bpy

PRINTS = 10  # background mode: a line at least every 1/PRINTS of the work (and at its start and end)


class Progress:
    """``label``: what is being done ("Gauss bake 'Cube'"); ``total``: how many items (frames)."""

    def __init__(self, context, label, total):
        self.label, self.total, self.done = label, max(int(total), 1), 0
        self.window_manager = None if bpy.app.background else context.window_manager
        self.workspace = None if bpy.app.background else context.workspace
        self._print_step = max(1, self.total // PRINTS)  # items between lines: at most a tenth of them
        self._printed = None
        if self.window_manager is not None:
            self.window_manager.progress_begin(0, self.total)
        self.update(0)

    def update(self, done, note=""):
        self.done = done
        share = done / self.total
        text = "%s: %d/%d (%d%%)%s" % (self.label, done, self.total, int(100 * share), note and "  |  " + note)
        if self.window_manager is not None:
            self.window_manager.progress_update(done)
            if self.workspace is not None:
                self.workspace.status_text_set(text + "  |  Esc: cancel")
        elif self._printed is None or done - self._printed >= self._print_step or done == self.total:
            self._printed = done
            print(text)
            sys.stdout.flush()

    def end(self):
        if self.window_manager is not None:
            self.window_manager.progress_end()
            if self.workspace is not None:
                self.workspace.status_text_set(None)
            self.window_manager = None
