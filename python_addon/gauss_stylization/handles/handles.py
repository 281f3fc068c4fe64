"""Pin handles: the pinned vertices of a live run as handles to drag (paper sections
3.3 and 5.1, Fig. 13: positional constraints).

Each connected part of a session's pins (vertices joined by edges of the loop
triangles) is one handle. A drag moves its pins' targets by one offset, parallel
to the view plane under the mouse or along an axis (X / Y / Z, as Blender's G:
global, then the object's own, then free again); the solver takes the new
targets at once (Solver.set_pin_positions, no re-factorization) and the mesh
follows at the next steps. Nothing here ends or steps a run; handle_tool.py
feeds it a live run's events and draws the handles.

Pixels are region pixels of the 3D view the drag happens in.
"""

import numpy as np
from bpy_extras import view3d_utils
from mathutils import Vector

PICK_PX = 12.0  # a press this close to a pin's dot (times the UI scale) grabs its handle
AXES = {'X': 0, 'Y': 1, 'Z': 2}


def pin_parts(pins, triangles):
    """Connected parts of the pinned vertices: a list of index arrays into ``pins``.

    pins:      #P vertex indices
    triangles: #T by 3 vertex indices; two pins are joined when a triangle has both.
    Parts are in the order of their first pin in ``pins``.
    """
    pins = np.asarray(pins, np.int64)
    if not len(pins):
        return []
    position = np.full(int(max(pins.max(), np.max(triangles, initial=0))) + 1, -1, np.int64)
    position[pins] = np.arange(len(pins))
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    edges = position[edges]
    edges = edges[(edges >= 0).all(axis=1)]
    label = np.arange(len(pins))
    while True:  # label propagation with pointer jumping: every part ends at its smallest member
        low = np.minimum(label[edges[:, 0]], label[edges[:, 1]])
        new = label.copy()
        np.minimum.at(new, edges[:, 0], low)
        np.minimum.at(new, edges[:, 1], low)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    order = np.argsort(label, kind="stable")
    starts = np.flatnonzero(np.diff(label[order], prepend=-1))
    return np.split(order, starts[1:])


def project(points, matrix_world, region, region_data):
    """Region pixels (N by 2) of object-space points (N by 3); NaN for points behind the eye."""
    to_clip = np.array(region_data.perspective_matrix @ matrix_world, np.float64)
    clip = np.column_stack([points, np.ones(len(points))]) @ to_clip.T
    w = clip[:, 3]
    ahead = w > 1e-9
    out = np.full((len(points), 2), np.nan)
    out[ahead, 0] = (clip[ahead, 0] / w[ahead] + 1.0) * 0.5 * region.width
    out[ahead, 1] = (clip[ahead, 1] / w[ahead] + 1.0) * 0.5 * region.height
    return out


class Handles:
    """The handles of one session: its pins (as the solver orders them), their current
    targets and the parts they form. Rebuilt when the solver's pins change.

    pins:    #P vertex indices, the solver's order
    targets: #P by 3 float64, the pins' targets (object space) as last sent to the solver
    parts:   index arrays into ``pins``, one per handle (pin_parts)
    drawn:   #P by 3 float32, the targets part after part, for the dots drawn every redraw;
             part k's rows are ``drawn[drawn_rows[k]]`` (a slice: a view, no copy)
    """

    def __init__(self, session):
        self.session = session
        self.pin_changes = session.pin_changes  # before reading: a change after it makes these stale
        solver = session.solver
        self.pins = np.asarray(solver.pinned, np.int64)
        self.targets = np.asarray(solver.pin_positions, np.float64).copy()
        self.parts = pin_parts(self.pins, session.solve_triangles)  # a proxy's pins are the proxy's vertices
        self.part_of = np.empty(len(self.pins), np.int64)  # pin (its row) -> its part
        ends = np.cumsum([len(members) for members in self.parts], dtype=np.int64)
        self.drawn_rows = [slice(int(end) - len(members), int(end)) for end, members in zip(ends, self.parts)]
        self.drawn = np.empty((len(self.pins), 3), np.float32)
        for index, members in enumerate(self.parts):
            self.part_of[members] = index
            self.drawn[self.drawn_rows[index]] = self.targets[members]

    def current(self):
        """Still the solver's pins? (A changed Pin Group re-pins the solver mid-run.) Asked at
        every redraw and mouse move, so it compares a count instead of the solver's arrays."""
        return self.pin_changes == self.session.pin_changes

    def part_at(self, x, y, region, region_data, ui_scale=1.0):
        """(part index, distance in pixels) of the handle with a pin nearest to region pixel
        (x, y) within PICK_PX, or None."""
        if not len(self.pins):
            return None
        pixels = project(self.targets, self.session.obj.matrix_world, region, region_data)
        distance = np.hypot(pixels[:, 0] - x, pixels[:, 1] - y)
        distance[np.isnan(distance)] = np.inf
        nearest = int(np.argmin(distance))
        if distance[nearest] > PICK_PX * ui_scale:
            return None
        return int(self.part_of[nearest]), float(distance[nearest])

    def move(self, part, targets):
        """Give the pins of ``part`` new targets (N by 3, object space) and send all to the
        solver. Returns False (and changes nothing) if the solver refuses them (too far)."""
        moved = self.targets.copy()
        moved[self.parts[part]] = targets
        try:
            self.session.move_pins(moved)
        except ValueError:
            return False
        self.targets = moved
        self.drawn[self.drawn_rows[part]] = moved[self.parts[part]]
        return True


class Drag:
    """One handle being dragged: where its pins started and how the mouse moves them."""

    def __init__(self, handles, part, region, region_data, mouse):
        self.handles, self.part = handles, part
        self.region, self.region_data = region, region_data
        self.start = handles.targets[handles.parts[part]].copy()
        self.matrix = np.array(handles.session.obj.matrix_world, np.float64)
        self.anchor = self.matrix[:3, :3] @ self.start.mean(axis=0) + self.matrix[:3, 3]  # world space
        self.mouse = tuple(mouse)
        self.axis = None  # None, or ('GLOBAL' | 'LOCAL', 0..2)

    def constrain(self, key):
        """X / Y / Z pressed: that global axis, the object's own on a second press, then free."""
        index = AXES[key]
        if self.axis == ('GLOBAL', index):
            self.axis = ('LOCAL', index)
        elif self.axis == ('LOCAL', index):
            self.axis = None
        else:
            self.axis = ('GLOBAL', index)

    def axis_vector(self):
        if self.axis is None:
            return None
        kind, index = self.axis
        vector = np.eye(3)[index] if kind == 'GLOBAL' else self.matrix[:3, index]
        return vector / np.linalg.norm(vector)

    def offset(self, mouse):
        """World-space offset of the handle for the mouse at region pixel ``mouse``."""
        axis = self.axis_vector()
        if axis is None:  # parallel to the view plane, the anchor under the mouse
            anchor = Vector(self.anchor)
            now = view3d_utils.region_2d_to_location_3d(self.region, self.region_data, mouse, anchor)
            then = view3d_utils.region_2d_to_location_3d(self.region, self.region_data, self.mouse, anchor)
            return np.array(now - then)
        return (self._along(axis, mouse) - self._along(axis, self.mouse)) * axis

    def _along(self, axis, mouse):
        """Where the mouse's ray passes the axis through the anchor: the parameter t of its
        nearest point anchor + t * axis (0 when looking along the axis)."""
        origin = np.array(view3d_utils.region_2d_to_origin_3d(self.region, self.region_data, mouse))
        ray = np.array(view3d_utils.region_2d_to_vector_3d(self.region, self.region_data, mouse))
        normal = np.cross(ray, np.cross(axis, ray))  # of the plane through the ray that the axis crosses
        crossing = np.dot(axis, normal)
        return 0.0 if abs(crossing) < 1e-9 else float(np.dot(origin - self.anchor, normal) / crossing)

    def update(self, mouse):
        """Move the handle for the mouse at ``mouse``. False if the solver refused the targets."""
        try:
            local = np.linalg.solve(self.matrix[:3, :3], self.offset(mouse))
        except np.linalg.LinAlgError:  # an object scaled to nothing: no way to move in its space
            return False
        return self.handles.move(self.part, self.start + local)

    def cancel(self):
        self.handles.move(self.part, self.start)
