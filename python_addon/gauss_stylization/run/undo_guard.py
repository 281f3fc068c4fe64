"""No undo steps while a live run is writing mid-run shapes into meshes.

A live run writes new coordinates into its meshes at every tick. Any undo push
during the run (a sidebar edit, a Move, a selection) would record a
half-stylized mesh, which Ctrl+Z after Enter, or redo after Esc, would then
bring back. While the preference ``undo_steps`` is 0 Blender records no step at
all and leaves the undo stack as it is; once the value is back, undo and redo
work as before. So a live run suspends undo while it runs, and whatever the
artist edited meanwhile lands in the one step the run pushes when it is kept
(or in the step operators.py pushes after Esc, see live_run.LiveRun.edited).

The artist's value must come back on every way a run ends, and must never be
saved as 0: Blender saves the preferences on quit when they are marked changed,
so the "changed" mark is put back too. resume() is idempotent; runs.py calls it
when the last run ends, on undo/redo, file loading and when the add-on is disabled.
"""

import bpy

# (undo_steps, is_dirty) of the preferences before the first run suspended undo; None when not suspended.
_saved = None


def _preferences():
    return bpy.context.preferences


def suspended():
    return _saved is not None


def suspend():
    """Stop undo pushes (nothing happens if they are stopped already)."""
    global _saved
    if _saved is not None:
        return
    preferences = _preferences()
    was_dirty = preferences.is_dirty
    _saved = (preferences.edit.undo_steps, was_dirty)
    preferences.edit.undo_steps = 0
    # Setting a preference marks them changed. Putting the mark back means that even a
    # quit that skipped resume() would not save 0 (unless something else changed them).
    preferences.is_dirty = was_dirty


def resume():
    """Give undo its steps back (nothing happens if it was not suspended)."""
    global _saved
    if _saved is None:
        return
    undo_steps, _was_dirty = _saved
    _saved = None
    preferences = _preferences()
    # Changed during the run, by the artist or by another preference: keep that change.
    dirty_now = preferences.is_dirty
    if preferences.edit.undo_steps == 0:  # the artist did not set another value meanwhile
        preferences.edit.undo_steps = undo_steps
    preferences.is_dirty = dirty_now
