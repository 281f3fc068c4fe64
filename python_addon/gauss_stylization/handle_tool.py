"""Pin handles during a live run: which presses grab a handle, the drag, and the dots.

``HandleTool.event`` is asked by the live run's modal operator before the run's own
click meanings: a left press within handles.PICK_PX of a pin's dot grabs that
pin's handle (nothing else sees the press), mouse moves drag it, X / Y / Z
constrain it, the release (or Enter) drops it where it is, Esc or a right-click
during the drag puts it back. Any other event is not its business (None), so a
click away from every pin keeps its meaning. The pins of every live run are
drawn as dots by a POST_VIEW draw handler, over the mesh, so hidden pins stay
grabbable.
"""

import gpu
import numpy as np

from . import gpu_compat, surface
from .handles import AXES, Drag, Handles
from .viewport import redraw_viewports, viewport_region_at

PIN, GRABBED, EDGE = (1.0, 0.55, 0.1, 1.0), (1.0, 1.0, 0.35, 1.0), (0.0, 0.0, 0.0, 1.0)
DOT_PX, EDGE_PX = 7.0, 10.0
MOVES = {'MOUSEMOVE', 'INBETWEEN_MOUSEMOVE'}

_grabbed = {}  # "session", "pins": what the draw handler highlights


class HandleTool:
    """The handles of one live run's sessions and the drag in progress (at most one)."""

    def __init__(self):
        self.handles = {}  # session -> Handles
        self.drag = None
        self.region = None

    def handles_of(self, session):
        found = self.handles.get(session)
        if found is None or not found.current():
            found = self.handles[session] = Handles(session)
        return found

    def event(self, context, event, sessions):
        """Take ``event`` ({'RUNNING_MODAL'}) if it grabs, drags or drops a handle, else None."""
        if self.drag is not None:
            return self._dragging(context, event)
        if event.type != 'LEFTMOUSE' or event.value != 'PRESS':
            return None
        found = viewport_region_at(context, event.mouse_x, event.mouse_y)
        if found is None or getattr(found[1], "data", None) is None:
            return None
        area, region = found
        x, y = event.mouse_x - region.x, event.mouse_y - region.y
        scale = context.preferences.system.ui_scale
        best = None
        for session in sessions:
            if not session.object_alive():
                continue
            handles = self.handles_of(session)
            hit = handles.part_at(x, y, region, region.data, scale)
            if hit is not None and (best is None or hit[1] < best[2]):
                best = (handles, hit[0], hit[1])
        if best is None:
            return None
        self.drag = Drag(best[0], best[1], region, region.data, (x, y))
        self.region = region
        _grabbed.update(session=best[0].session, pins=best[0].pins[best[0].parts[best[1]]])
        area.tag_redraw()
        return {'RUNNING_MODAL'}

    def _dragging(self, context, event):
        drag = self.drag
        mouse = (event.mouse_x - self.region.x, event.mouse_y - self.region.y)
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
        redraw_viewports(context)
        return {'RUNNING_MODAL'}

    def drop(self):
        self.drag = self.region = None
        _grabbed.clear()

    def hint(self):
        """What the status bar says during a drag, or None."""
        if self.drag is None:
            return None
        axis = self.drag.axis
        where = "free (X / Y / Z: along an axis)" if axis is None else "along %s %s (press again: %s)" % (
            axis[0].lower(), "XYZ"[axis[1]], "local axis" if axis[0] == 'GLOBAL' else "free")
        return "Dragging a handle %s; release: drop, Esc / right-click: put back" % where


def draw_pins():
    """The draw handler: every live session's pins as dots, the grabbed handle's brighter."""
    gpu.state.depth_test_set('NONE')
    gpu.state.blend_set('ALPHA')
    for session in surface.live_sessions():
        if not session.object_alive():
            continue
        pins = np.asarray(session.solver.pinned)
        if not len(pins):
            continue
        targets = np.asarray(session.solver.pin_positions, np.float32)
        grabbed = np.isin(pins, _grabbed["pins"]) if _grabbed.get("session") is session else np.zeros(len(pins), bool)
        with gpu.matrix.push_pop():
            gpu.matrix.multiply_matrix(session.obj.matrix_world)
            gpu_compat.draw_points(targets, EDGE, EDGE_PX)
            gpu_compat.draw_points(targets[~grabbed], PIN, DOT_PX)
            gpu_compat.draw_points(targets[grabbed], GRABBED, DOT_PX)
    gpu.state.blend_set('NONE')


_handler = gpu_compat.ViewDrawHandler("Gauss pin handles", draw_pins, 'POST_VIEW')


def register():
    _handler.add()


def unregister():
    _handler.remove()
    _grabbed.clear()
