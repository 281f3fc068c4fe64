"""Editing a Custom style on the Gauss sphere overlay: a click on the sphere adds a
preferred normal in that direction (dragging on moves it), a drag that starts on a
dot moves that normal, a right-click removes the normal nearest to it.

The add-on's key map sends left and right presses over a 3D view to
OBJECT_OT_gauss_sphere_edit first; a press that does not hit an editable sphere
passes through untouched, so clicks elsewhere keep their meaning. A live run's modal
operator sees presses before any key map, so its event handler list (modal_events) asks
``live_run_presses`` first, which lets the presses claims() wants through to the key map.
A live run picks an edit up at its next step (custom normals rebuild its styles).
"""

import bpy
import numpy as np

from ..run import modal_events, runs
from ..settings import styles
from ..settings.schema import CUSTOM
from ..view.viewport import viewport_region_at
from . import gauss_sphere, sphere_overlay

DOT_PICK_PX = 10.0   # a press this close to a dot (times the UI scale) grabs it
BUTTONS = ('LEFTMOUSE', 'RIGHTMOUSE')
KEYMAPS = ("Object Mode",)  # pressed-button items of this key map come before selection's


class Hit:
    """A press on an editable sphere: the object, its active Custom slot, where the sphere
    is, the object -> view rotation, the object-space direction under the mouse."""

    def __init__(self, obj, slot, where, turn, direction, on_sphere):
        self.obj, self.slot, self.where, self.turn = obj, slot, where, turn
        self.direction, self.on_sphere = direction, on_sphere

    def normals(self):
        """The slot's custom normals as the sphere shows them (object space, unit, rotated)."""
        stored = np.array(self.slot.custom_normal_list(), np.float64).reshape(-1, 3)
        stored /= np.linalg.norm(stored, axis=1)[:, None]
        return stored @ styles.rotation_matrix(self.slot).T

    def stored(self, direction):
        """The custom-normal vector that shows as ``direction`` (undoes the slot's rotation)."""
        return tuple(styles.rotation_matrix(self.slot).T @ direction)

    def dot_at(self, x, y, ui_scale):
        """Index of the custom normal whose front-facing dot is nearest to pixel (x, y), within
        DOT_PICK_PX; None if there is none."""
        seen = self.normals() @ self.turn.T
        pixels = gauss_sphere.to_pixels(seen, self.where)
        distance = np.hypot(pixels[:, 0] - x, pixels[:, 1] - y)
        distance[seen[:, 2] <= 0] = np.inf
        if not len(distance) or distance.min() > DOT_PICK_PX * ui_scale:
            return None
        return int(np.argmin(distance))


def hit_at(context, area, region, x, y, anywhere=False):
    """The Hit at region pixel (x, y) of a 3D view, if the active object's sphere is shown
    there with a Custom slot active and (unless ``anywhere``) the pixel is on the sphere."""
    obj = sphere_overlay.shown_object(context)
    region_data = getattr(region, "data", None)
    if obj is None or region_data is None:
        return None
    slot = styles.active_slot(obj.gauss_stylization)
    if slot is None or slot.preset != CUSTOM:
        return None
    where = sphere_overlay.placement(area, region)
    turn = sphere_overlay.view_rotation(region_data, obj)
    view, on_sphere = gauss_sphere.from_pixel(x, y, where)
    if not (on_sphere or anywhere):
        return None
    return Hit(obj, slot, where, turn, turn.T @ view, on_sphere)


def claims(context, event):
    """Does a press belong to sphere editing (a live run must then let it through)?"""
    if event.type not in BUTTONS or event.value != 'PRESS':
        return False
    found = viewport_region_at(context, event.mouse_x, event.mouse_y)
    if found is None:
        return False
    area, region = found
    return hit_at(context, area, region, event.mouse_x - region.x, event.mouse_y - region.y) is not None


def live_run_presses(_run, context, event):
    """modal_events handler: a press on the editable sphere during a live run goes on to the
    key map (this module's operator) instead of keeping or cancelling the run."""
    return {'PASS_THROUGH'} if claims(context, event) else None


class OBJECT_OT_gauss_sphere_edit(bpy.types.Operator):
    """Edit the active Custom style on the Gauss sphere: click to add a normal, drag a dot to
    move it, right-click to remove the nearest"""
    bl_idname = "object.gauss_sphere_edit"
    bl_label = "Edit on Gauss Sphere"
    # No 'UNDO': an undo step in the middle of a live run would hold its half-done mesh;
    # finished edits push one themselves when no run is live (_push_undo).
    bl_options = {'REGISTER', 'INTERNAL'}

    def invoke(self, context, event):
        x, y = event.mouse_region_x, event.mouse_region_y
        hit = hit_at(context, context.area, context.region, x, y)
        if hit is None:
            return {'PASS_THROUGH'}
        if event.type == 'RIGHTMOUSE':
            return self._remove_nearest(context, hit)
        ui_scale = context.preferences.system.ui_scale
        normals = hit.slot.custom_normal_list()
        self._index = hit.dot_at(x, y, ui_scale)
        self._before = list(normals)
        if self._index is None:  # a new normal, which the drag then moves
            hit.slot.set_custom_normals(normals + [hit.stored(hit.direction)])
            self._index = len(normals)
        hit.slot.active_normal_index = self._index
        self._obj, self._slot_index = hit.obj, hit.obj.gauss_stylization.active_style_index
        context.area.tag_redraw()
        context.window_manager.modal_handler_add(self)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type == 'MOUSEMOVE':
            hit = self._hit(context, event)
            if hit is not None:
                hit.slot.custom_normals[self._index].vector = hit.stored(hit.direction)
                context.area.tag_redraw()
            return {'RUNNING_MODAL'}
        if event.type == 'LEFTMOUSE' and event.value == 'RELEASE':
            _push_undo(self._obj)
            return {'FINISHED'}
        if event.type in {'ESC', 'RIGHTMOUSE'} and event.value == 'PRESS':
            slot = self._slot()
            if slot is not None:
                slot.set_custom_normals(self._before)
            context.area.tag_redraw()
            return {'CANCELLED'}
        return {'PASS_THROUGH'}  # timers (a live run goes on), navigation

    def _slot(self):
        try:
            settings = self._obj.gauss_stylization
        except ReferenceError:  # the object went away during the drag
            return None
        slot = styles.active_slot(settings)
        same = slot is not None and settings.active_style_index == self._slot_index and slot.preset == CUSTOM
        return slot if same and self._index < len(slot.custom_normals) else None

    def _hit(self, context, event):
        if self._slot() is None:
            return None
        return hit_at(context, context.area, context.region, event.mouse_region_x, event.mouse_region_y,
                      anywhere=True)

    def _remove_nearest(self, context, hit):
        normals = hit.slot.custom_normal_list()
        if len(normals) < 2:
            self.report({'WARNING'}, "A Custom style keeps at least one normal")
            return {'CANCELLED'}
        nearest = int(np.argmax(hit.normals() @ hit.direction))
        hit.slot.set_custom_normals(normals[:nearest] + normals[nearest + 1:])
        context.area.tag_redraw()
        _push_undo(hit.obj)
        return {'FINISHED'}


def _push_undo(obj):
    if not runs.is_running(obj):  # a live run's edits become part of its own undo step
        bpy.ops.ed.undo_push(message="Edit on Gauss Sphere")


classes = (OBJECT_OT_gauss_sphere_edit,)
_keymap_items = []


def register():
    modal_events.add(live_run_presses, modal_events.OVERLAYS)
    keyconfig = bpy.context.window_manager.keyconfigs.addon
    if keyconfig is None:  # background mode: no key maps
        return
    for name in KEYMAPS:
        keymap = keyconfig.keymaps.new(name=name, space_type='EMPTY')
        for button in BUTTONS:
            _keymap_items.append((keymap, keymap.keymap_items.new(
                OBJECT_OT_gauss_sphere_edit.bl_idname, button, 'PRESS')))


def unregister():
    modal_events.remove(live_run_presses)
    for keymap, item in _keymap_items:
        keymap.keymap_items.remove(item)
    _keymap_items.clear()
