"""How a live run answers the events it sees: an ordered list of handlers.

The Stylize operator's modal() hands every event except its timer to
``dispatch``. Handlers are asked in ascending ``order``; the first that returns
a result decides, and an event nobody takes goes on to Blender (PASS_THROUGH),
so navigation, the sidebar and every other editor keep working during a run.

A handler is ``handler(run, context, event)`` and returns None (not its
business) or what modal() returns: {'RUNNING_MODAL'} to take the event,
{'PASS_THROUGH'} to give it to Blender after all, or the result of
``run.end(context, keep)`` when it ends the run. ``run`` is the modal operator:

    run.end(context, keep, why=None) -> {'FINISHED'} / {'CANCELLED'}: keep or restore all objects
    run.preparing           -> True while the solvers are still being set up
    run.live.sessions       -> the session.Session of each object in the run
    run.scratch             -> dict for handlers' own state during this run, by handler name
    run.notes               -> dict of texts the status bar shows after the run's own, by name; a
                               KeysNote there takes the place of the run's texts while it is set
    run.show_status(context)   redraws the header and status bar (after a handler changed notes)

Another feature adds its handler with ``add(handler, order, on_end)`` when it
registers (and removes it when it unregisters); e.g. pin handles take presses
on pins at order HANDLES, before a plain click keeps the result, and a handle
being dragged takes its events at DRAGS, before Esc or Enter end the run. ``on_end(run,
context, keep)``, if given, is called once when the run ends, however it ends,
before the meshes are kept or restored.
"""

from ..view.viewport import drag_distance_exceeded, free_viewport_at
from .runs import UNDO_CANCELLED

DRAGS = 50      # a drag in progress (a pin handle): its Esc puts it back, its Enter drops it
KEYS = 100      # Enter, Esc, Ctrl+Z, Ctrl+Shift+Z, Tab (not Ctrl+Tab)
OVERLAYS = 150  # things drawn over the viewport that take presses (the Gauss sphere), over the pins
HANDLES = 200   # for things in the viewport that take presses and drags (pin handles)
CLICKS = 300    # a plain click in the free viewport keeps, a right-click cancels

_handlers = []  # (order, handler, on_end), sorted by order


class KeysNote(str):
    """A note (run.notes) of a handler that has the keys for now, e.g. a handle being dragged: the
    header and status bar show it alone, so that no key is said to do two things."""


def add(handler, order, on_end=None):
    """Ask ``handler`` about every event of a live run, after those of lower order."""
    remove(handler)
    _handlers.append((order, handler, on_end))
    _handlers.sort(key=lambda item: item[0])


def remove(handler):
    _handlers[:] = [item for item in _handlers if item[1] is not handler]


def dispatch(run, context, event):
    if event.value == 'PRESS':
        # A press starts a new click, whoever takes it: a press the click handler never saw
        # (taken by a handle, or by Blender's gizmo) must not pair with an older one.
        run.scratch.pop("click", None)
    for _order, handler, _on_end in tuple(_handlers):
        result = handler(run, context, event)
        if result is not None:
            return result
    return {'PASS_THROUGH'}


def run_ended(run, context, keep):
    """Tell every handler that asked (on_end) that ``run`` ends; called once per run."""
    for _order, _handler, on_end in tuple(_handlers):
        if on_end is not None:
            on_end(run, context, keep)


# -- the run's own handlers ----------------------------------------------------------------

def keys(run, context, event):
    """Enter keeps, Esc cancels, so do Ctrl+Z and Ctrl+Shift+Z (saying so); Tab (Edit Mode, which
    would end the run) is blocked, Ctrl+Tab goes on to the mode pie. During the set-up only Esc and
    undo act (there is nothing to keep yet)."""
    if event.value != 'PRESS':
        return None
    if event.type == 'ESC':
        return run.end(context, keep=False)
    if event.type == 'Z' and (event.ctrl or event.oskey):
        return run.end(context, keep=False, why=UNDO_CANCELLED % ("redo" if event.shift else "undo"))
    if run.preparing:
        return None
    if event.type in {'RET', 'NUMPAD_ENTER'}:
        return run.end(context, keep=True)
    if event.type == 'TAB' and not event.ctrl:  # Ctrl+Tab: the mode pie, the way to Weight Paint
        return {'RUNNING_MODAL'}
    return None


def clicks(run, context, event):
    """A plain click (press and release without a drag) in the free viewport keeps the result;
    a right-click there cancels. Presses elsewhere (gizmo, headers, toolbar, sidebar, other
    editors) and every drag belong to Blender, so the press always goes on to it."""
    if run.preparing or context.mode == 'PAINT_WEIGHT':  # in Weight Paint a click is a dab of paint
        return None
    x, y = event.mouse_x, event.mouse_y
    if event.type == 'MOUSEMOVE':  # a drag that came back to where it started is still a drag
        pressed = run.scratch.get("click")
        if pressed is not None and drag_distance_exceeded(context, pressed, (x, y)):
            run.scratch["click"] = None
        return None
    if event.type not in {'LEFTMOUSE', 'RIGHTMOUSE'}:
        return None
    if event.type == 'RIGHTMOUSE':
        if event.value == 'PRESS' and free_viewport_at(context, x, y):
            return run.end(context, keep=False)
        return None
    if event.value == 'PRESS':
        run.scratch["click"] = (x, y) if free_viewport_at(context, x, y) else None
        return None
    if event.value == 'RELEASE':
        pressed = run.scratch.pop("click", None)
        if pressed is not None and not drag_distance_exceeded(context, pressed, (x, y)):
            return run.end(context, keep=True)
    return None


add(keys, KEYS)
add(clicks, CLICKS)
