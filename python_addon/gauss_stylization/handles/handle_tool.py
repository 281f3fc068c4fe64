"""Pin handles during a live run: which presses grab a handle, the drag, and the dots.

Two handlers in the live run's event list (modal_events): ``grab`` (order
HANDLES) takes a left press in the free viewport within handles.PICK_PX of a pin's
dot and grabs that pin's handle (nothing else sees the press; a press away from
every pin keeps its meaning); ``drag`` (order DRAGS, before the run's keys) takes
the events of a drag in progress: mouse moves drag it, X / Y / Z constrain it, the
release (or Enter) drops it where it is, Esc or a right-click puts it back. Every
object of a run offers its own pins as handles, except while its solver is being
re-factored for a new Pin Group (it must not be touched then). A run keeps its
HandleTool in run.scratch and its drag hint in run.notes. The pins of every live
run are drawn as dots by a POST_VIEW draw handler, over the mesh, so hidden pins
stay grabbable.
"""

import gpu

from ..run import modal_events, runs
from ..view import gpu_compat
from ..view.viewport import free_viewport_at, redraw_viewports, viewport_region_at
from .handles import AXES, Drag, Handles

PIN, GRABBED, EDGE = (1.0, 0.55, 0.1, 1.0), (1.0, 1.0, 0.35, 1.0), (0.0, 0.0, 0.0, 1.0)
DOT_PX, EDGE_PX = 7.0, 10.0
MOVES = {'MOUSEMOVE', 'INBETWEEN_MOUSEMOVE'}
NAME = "handles"  # the key of this tool's state in run.scratch and run.notes


def usable(session):
    """May ``session``'s pins be read and moved now?"""
    return session.busy is None and session.object_alive()


class HandleTool:
    """The handles of one live run's sessions and the drag in progress (at most one)."""

    def __init__(self):
        self.handles = {}  # session -> Handles
        self.drag = None

    def handles_of(self, session):
        found = self.handles.get(session)
        if found is None or not found.current():
            found = self.handles[session] = Handles(session)
        return found

    def grab(self, context, event, sessions):
        """Grab the handle of ``sessions``' pin under a left press ({'RUNNING_MODAL'}), or None
        if no pin is there."""
        x, y = event.mouse_x, event.mouse_y
        found = viewport_region_at(context, x, y)
        if found is None:
            return None
        area, region = found
        if getattr(region, "data", None) is None:
            return None
        x, y = x - region.x, y - region.y
        scale = context.preferences.system.ui_scale
        best = None
        for session in sessions:
            if not usable(session):
                continue
            handles = self.handles_of(session)
            hit = handles.part_at(x, y, region, region.data, scale)
            if hit is not None and (best is None or hit[1] < best[2]):
                best = (handles, hit[0], hit[1])
        if best is None:
            return None
        self.drag = Drag(best[0], best[1], region, region.data, (x, y))
        area.tag_redraw()
        return {'RUNNING_MODAL'}

    def dragging(self, context, event):
        """Move, constrain, drop or put back the grabbed handle; None for events it leaves alone."""
        drag = self.drag
        if not usable(drag.handles.session) or not drag.handles.current():
            self.drop()  # its object went away, or its Pin Group changed under the drag
            return None
        mouse = (event.mouse_x - drag.region.x, event.mouse_y - drag.region.y)
        if event.type in MOVES:
            drag.update(mouse)
        elif event.type in AXES and event.value == 'PRESS':
            drag.constrain(event.type)
            drag.update(mouse)
        elif (event.type == 'LEFTMOUSE' and event.value == 'RELEASE') or (
                event.type in {'RET', 'NUMPAD_ENTER'} and event.value == 'PRESS'):
            self.drop()
        elif event.type in {'ESC', 'RIGHTMOUSE'} and event.value == 'PRESS':
            drag.cancel()
            self.drop()
        else:
            return None  # timers (the run goes on stepping), navigation
        redraw_viewports(context, sidebars=False)
        return {'RUNNING_MODAL'}

    def drop(self):
        self.drag = None

    def grabbed_part(self, session):
        """The index of ``session``'s handle being dragged, or None."""
        drag = self.drag
        if drag is None or drag.handles.session is not session:
            return None
        return drag.part

    def hint(self):
        """What the header and status bar say during a drag (instead of the run's keys: a drag's Esc
        puts the handle back, it does not cancel the run), or None."""
        if self.drag is None:
            return None
        axis = self.drag.axis
        key = None if axis is None else "XYZ"[axis[1]]
        where = "free (X / Y / Z: along an axis)" if axis is None else "along %s %s (%s again: %s)" % (
            axis[0].lower(), key, key, "local" if axis[0] == 'GLOBAL' else "free")
        return modal_events.KeysNote(
            "Dragging a handle %s  |  Release / Enter: drop  |  Esc / Right-click: put back" % where)


def tool_of(run):
    """The HandleTool of a live run (made at its first use)."""
    tool = run.scratch.get(NAME)
    if tool is None:
        tool = run.scratch[NAME] = HandleTool()
    return tool


def _show_hint(run, context, tool):
    """The drag's hint in the header and status bar, redrawn only when it changed (a drag sends a
    mouse move per pixel; the run's ticks refresh the rest of the status text)."""
    hint = tool.hint()
    if NAME in run.notes and run.notes[NAME] == hint:
        return
    run.notes[NAME] = hint
    run.show_status(context)


def grab(run, context, event):
    """modal_events handler (HANDLES): a left press on a pin grabs its handle."""
    if event.type != 'LEFTMOUSE' or event.value != 'PRESS' or run.preparing:
        return None
    if context.mode == 'PAINT_WEIGHT':  # a press there paints (the status bar says so)
        return None
    if not free_viewport_at(context, event.mouse_x, event.mouse_y):
        return None  # headers, sidebar, gizmo, other editors: Blender's
    tool = tool_of(run)
    taken = tool.grab(context, event, run.live.sessions)
    if taken is not None:
        _show_hint(run, context, tool)
    return taken


def drag(run, context, event):
    """modal_events handler (DRAGS): the events of a handle being dragged."""
    tool = run.scratch.get(NAME)
    if tool is None or tool.drag is None:
        return None
    taken = tool.dragging(context, event)
    if taken is not None or tool.drag is None:
        _show_hint(run, context, tool)
    return taken


def run_ended(run, _context, _keep):
    """modal_events on_end: a drag in progress ends with its run (where it is: a kept run keeps it)."""
    tool = run.scratch.get(NAME)
    if tool is not None:
        tool.drop()


def draw_pins():
    """The draw handler: every live session's pins as dots, the grabbed handle's brighter.

    Drawn from the handles' own targets (moved by the drag), not the solver's: no copy of the
    solver's arrays at every redraw, and the grabbed handle's dots are a slice of the others.
    (gpu_compat.ViewDrawHandler puts the depth and blend state back afterwards.)"""
    gpu.state.depth_test_set('NONE')
    gpu.state.blend_set('ALPHA')
    for run in runs.live_runs():
        for session in run.sessions:  # a bake has none (and no scratch for a tool)
            if not usable(session):
                continue
            tool = tool_of(run)
            handles = tool.handles_of(session)
            points = handles.drawn
            if not len(points):
                continue
            part = tool.grabbed_part(session)
            grabbed = handles.drawn_rows[part] if part is not None else slice(len(points), len(points))
            with gpu.matrix.push_pop():
                gpu.matrix.multiply_matrix(session.obj.matrix_world)
                gpu_compat.draw_points(points, EDGE, EDGE_PX)
                gpu_compat.draw_points(points[:grabbed.start], PIN, DOT_PX)
                gpu_compat.draw_points(points[grabbed.stop:], PIN, DOT_PX)
                gpu_compat.draw_points(points[grabbed], GRABBED, DOT_PX)


_handler = gpu_compat.ViewDrawHandler("Gauss pin handles", draw_pins, 'POST_VIEW')


def register():
    modal_events.add(drag, modal_events.DRAGS)
    modal_events.add(grab, modal_events.HANDLES, on_end=run_ended)
    _handler.add()


def unregister():
    _handler.remove()
    modal_events.remove(grab)
    modal_events.remove(drag)
