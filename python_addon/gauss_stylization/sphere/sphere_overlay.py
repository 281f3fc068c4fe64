"""The Gauss sphere overlay: a draw handler (POST_PIXEL, gpu module) that shows, in the
bottom-left corner of every 3D view, the sphere of directions of the active object
(when its ``show_gauss_sphere`` is on): the active style's g as a heat map (its
rotation applied), its preferred normals as white dots, and the mesh's face normals
as a cloud of points (an area-weighted sample) that follows a live run.

What it draws is computed here; where (gauss_sphere.frame) and how (gpu_compat) live
in their own modules, and sphere_editing.py uses the same placement for clicks.
"""

import blf
import bpy
import gpu
import numpy as np

from .. import native
from ..errors import NativeModuleError, SettingsError
from ..run import runs
from ..settings import styles
from ..settings.fields import read_all
from ..settings.schema import CUSTOM
from ..view import gpu_compat
from . import directions, gauss_sphere, surface

MAX_POINTS = 2000  # face normals drawn at most (a sample weighted by area)
BACKDROP = (0.08, 0.08, 0.08, 0.55)
NORMAL_POINTS = (0.35, 0.95, 1.0, 0.6)
DOT, DOT_EDGE, DOT_BEHIND = (1.0, 1.0, 1.0, 1.0), (0.0, 0.0, 0.0, 1.0), (1.0, 1.0, 1.0, 0.35)
ACTIVE_DOT = (1.0, 0.55, 0.1, 1.0)  # the Custom normal selected in the panel's list
TEXT = (1.0, 1.0, 1.0, 0.9)
AXIS_COLOURS = {"X": (1.0, 0.33, 0.33), "Y": (0.55, 0.86, 0.2), "Z": (0.3, 0.56, 1.0)}  # Blender's gizmo's
AXIS_BEHIND_ALPHA = 0.45

_sphere = None   # (vertices, triangles) of the icosphere, built on first use
_colours = {}    # key of the style's fields -> (colours of the sphere's vertices, preferred normals)
_sample = {}     # "key": mesh identity, "triangles": the sampled triangles (S by 3)


def shown_object(context):
    """The active object if it is a mesh whose sphere is switched on, else None."""
    obj = context.active_object
    if obj is None or obj.type != 'MESH' or not obj.gauss_stylization.show_gauss_sphere:
        return None
    return obj


def view_rotation(region_data, obj):
    """V (3 by 3): object-space directions -> the view's (x right, y up, z to the viewer)."""
    view = np.array(region_data.view_matrix.to_3x3(), np.float64)
    return view @ surface.world_rotation(obj)


def placement(area, region):
    """The sphere's Frame in ``region`` (a 3D view's main region), clear of the toolbar
    when the toolbar is drawn over the region."""
    inset = 0.0
    for other in area.regions:
        if other.type == 'TOOLS' and other.width > 1:
            inset = max(inset, other.x + other.width - region.x)
    return gauss_sphere.frame(region.width, region.height, inset, bpy.context.preferences.system.ui_scale)


def style_look(gauss_core, obj, slot):
    """(colours of the sphere's vertices N by 4, preferred normals K by 3 in object space)
    of ``slot``'s style; cached until one of its style fields changes."""
    key = (obj.as_pointer(), repr(read_all(styles.STYLE_FIELDS, slot)))
    if key not in _colours:
        style = styles.checked_style(gauss_core, obj, slot)
        _colours.clear()
        _colours[key] = (gauss_sphere.heat_colours(style.value(sphere()[0])), np.asarray(style.normals))
    return _colours[key]


def sphere():
    global _sphere
    if _sphere is None:
        _sphere = gauss_sphere.icosphere()
    return _sphere


def face_normal_sample(obj):
    """Unit normals (S by 3, object space) of up to MAX_POINTS triangles of the mesh now.

    Which triangles is decided once per mesh (and per run), weighted by their areas
    then; their normals are computed afresh at every draw, so they follow a run."""
    coords, triangles = surface.coords_and_triangles(obj, cached_topology=True)
    mesh = obj.data
    key = (mesh.as_pointer(), len(coords), len(triangles), runs.session_of(obj) is not None)
    if _sample.get("key") != key:
        _, areas = directions.triangle_normals(coords, triangles)
        _sample.update(key=key, triangles=triangles[directions.area_sample(areas, MAX_POINTS)])
    normals, areas = directions.triangle_normals(coords, _sample["triangles"])
    return normals[areas > 0]


def draw(context):
    """The draw handler's body: everything it shows for the active object."""
    obj = shown_object(context)
    area, region = context.area, context.region
    if obj is None or area is None or region is None or context.region_data is None:
        return
    settings = obj.gauss_stylization
    slot = styles.active_slot(settings)
    where = placement(area, region)
    turn = view_rotation(context.region_data, obj)
    vertices, triangles = sphere()
    seen = vertices @ turn.T
    colours, preferred, problem = None, np.empty((0, 3)), None
    if slot is None:
        problem = "no style slot"
    elif slot.preset == CUSTOM and not slot.custom_normals:
        problem = "click the sphere to add a normal"
    else:
        try:
            colours, preferred = style_look(native.core(), obj, slot)
        except (SettingsError, NativeModuleError) as exc:
            problem = str(exc)
    if colours is None:
        colours = np.tile([0.3, 0.3, 0.3, 1.0], (len(vertices), 1))

    # gpu_compat.ViewDrawHandler puts the blend and depth state back after the handler.
    gpu.state.blend_set('ALPHA')
    gpu.state.depth_test_set('NONE')
    gpu_compat.draw_uniform(gauss_sphere.disc(where, grow=1.06), BACKDROP)
    gpu_compat.draw_triangles(gauss_sphere.to_pixels(seen, where), gauss_sphere.shaded(colours, seen),
                              gauss_sphere.facing(seen, triangles))
    normals = face_normal_sample(obj) @ turn.T
    gpu_compat.draw_points(gauss_sphere.to_pixels(normals[normals[:, 2] > 0], where), NORMAL_POINTS, 2.0)
    # Under the dots: a preset's preferred normals lie along the axes, and a dot must stay visible.
    for name, x, y, facing in gauss_sphere.axis_labels(turn, where):
        colour = AXIS_COLOURS[name] + ((1.0,) if facing else (AXIS_BEHIND_ALPHA,))
        _text(name, x, y, colour, centred=True)
    dots = preferred @ turn.T
    front, back = dots[dots[:, 2] > 0], dots[dots[:, 2] <= 0]
    gpu_compat.draw_points(gauss_sphere.to_pixels(back, where), DOT_BEHIND, 5.0)
    front_pixels = gauss_sphere.to_pixels(front, where)
    gpu_compat.draw_points(front_pixels, DOT_EDGE, 11.0)
    gpu_compat.draw_points(front_pixels, DOT, 7.0)
    active = active_normal(slot, len(preferred))
    if active is not None:
        seen = dots[active]
        pixel = gauss_sphere.to_pixels(seen[None], where)
        gpu_compat.draw_points(pixel, DOT_EDGE, 13.0)
        gpu_compat.draw_points(pixel, ACTIVE_DOT if seen[2] > 0 else ACTIVE_DOT[:3] + (0.5,), 9.0)
    _label(where, "%s%s" % (slot.name if slot else "Gauss sphere", "  (%s)" % problem if problem else ""))


def active_normal(slot, count):
    """Index of the Custom normal selected in the panel's list among ``count`` drawn ones, or None."""
    if slot is None or slot.preset != CUSTOM or not 0 <= slot.active_normal_index < count:
        return None
    return slot.active_normal_index


def _text(text, x, y, colour, centred=False):
    font = 0
    blf.size(font, 11.0 * bpy.context.preferences.system.ui_scale)  # no DPI argument: gone in 4.0
    blf.color(font, *colour)
    if centred:
        width, height = blf.dimensions(font, text)
        x, y = x - width / 2.0, y - height / 2.0
    blf.position(font, x, y, 0.0)
    blf.enable(font, blf.SHADOW)  # readable over the heat map and over a light grid alike
    blf.shadow(font, 3, 0.0, 0.0, 0.0, 0.9)
    blf.shadow_offset(font, 1, -1)
    blf.draw(font, text)
    blf.disable(font, blf.SHADOW)


def _label(where, text):
    scale = bpy.context.preferences.system.ui_scale
    _text(text, where.x - where.radius, where.y + where.radius * 1.08 + 14.0 * scale, TEXT)


_handler = gpu_compat.ViewDrawHandler("Gauss sphere overlay", lambda: draw(bpy.context), 'POST_PIXEL')


def register():
    _handler.add()


def unregister():
    _handler.remove()
    _colours.clear()
    _sample.clear()
