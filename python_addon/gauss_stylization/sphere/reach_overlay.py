"""The Style Reach overlay: every visible mesh in Object Mode whose ``show_style_reach`` is on is drawn
over in the colours of style_reach (its faces' angles to what their styles prefer), following a live run,
with the colour scale in the bottom-right corner of every 3D view. In Edit, Sculpt and paint modes the
object is left as Blender draws it (the overlay would hide the selection, the brush's work and the
weights).

The angles are computed again when the shape, the styles, the Regions or the Method change, at most
every REFRESH_SECONDS and less often on a mesh whose angles take long to compute (at most REFRESH_SHARE of
the time); a timer redraws once more after the last change. The Regions' weights and the triangles are
read again when the object comes back from another mode (Weight Paint and Edit Mode are where they
change). The drawing keeps one GPU batch per object until the angles change.
"""

import time

import blf
import bpy
import gpu
import numpy as np

from .. import native
from ..errors import NativeModuleError, SettingsError
from ..mesh import mesh_io
from ..run import runs
from ..settings import paint_curve, styles
from ..settings.fields import read_all
from ..view import gpu_compat, viewport
from . import directions, style_reach
from .surface import surface_arrays

REFRESH_SECONDS = 0.25
REFRESH_SHARE = 0.2
LIFT = 1e-3  # the overlay floats this share of the bounding box's diagonal above the surface (no z-fighting)
ALPHA = 0.85
TEXT = (1.0, 1.0, 1.0, 0.9)
# obj pointer -> {"key", "time", "cost", "angles" (#T), "positions", "colours", "batch", "problem",
#                 "mode", "stamp", "weights_key", "weights"}; entries of objects no longer shown are dropped
_cache = {}


def shown_objects(context):
    return [obj for obj in context.visible_objects
            if obj.type == 'MESH' and obj.gauss_stylization.show_style_reach]


def _stamp(entry, obj):
    """A number that changes whenever ``obj`` changed mode since the last drawing."""
    if entry.get("mode") != obj.mode:
        entry["mode"] = obj.mode
        entry["stamp"] = entry.get("stamp", 0) + 1
    return entry.get("stamp", 0)


def check_regions(obj):
    """SettingsError naming a slot whose Region is a vertex group that no longer exists."""
    names = {group.name for group in obj.vertex_groups}
    for slot in obj.gauss_stylization.styles:
        if slot.vertex_group and slot.vertex_group not in names:
            raise SettingsError("Style '%s': its Region, vertex group '%s', no longer exists"
                                % (slot.name, slot.vertex_group))


def _face_weights(obj, entry):
    """(#T, #slots) face weights of the slots' Regions, as the solver has them: from the live run's
    group weights, else read from the vertex groups (again after the object was in another mode)."""
    session = runs.session_of(obj)
    settings = obj.gauss_stylization
    groups = tuple(slot.vertex_group for slot in settings.styles)
    steepness = paint_curve.steepness_of(settings)
    mesh = obj.data
    source = (("run", id(session), id(session.weights)) if session is not None else
              ("mesh", mesh.as_pointer(), len(mesh.vertices), len(mesh.polygons), entry.get("stamp")))
    key = (source, groups, settings.uncovered, steepness)
    if entry.get("weights_key") != key:
        if session is not None:
            arrays, weights = session.arrays, session.weights
        else:
            arrays = mesh_io.MeshArrays(mesh)
            weights = mesh_io.read_group_weights(obj) if any(groups) else {}
        entry["weights"] = styles.face_weights(arrays, weights, list(groups), settings.uncovered, steepness)
        entry["weights_key"] = key
    return entry["weights"]


def surface_of(obj, cached_topology=False, stamp=None):
    """(coords #V by 3, triangles #T by 3, tri_polygon #T) of ``obj`` now: the live run's shape, else
    the base mesh (surface.surface_arrays), or the shape keys' mix as shown when the mesh has keys."""
    coords, triangles, tri_polygon = surface_arrays(obj, cached_topology, stamp)
    keys = obj.data.shape_keys
    if runs.session_of(obj) is None and keys is not None and len(keys.key_blocks) > 1:
        shown = _shown_coords(obj)
        if shown is not None:
            coords = shown
    return coords, triangles, tri_polygon


def _shown_coords(obj):
    """The vertices as shown (shape keys mixed in), when the shown mesh has the base mesh's vertices."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        if len(mesh.vertices) != len(obj.data.vertices):
            return None
        return mesh_io.read_vertex_coords(mesh)
    finally:
        evaluated.to_mesh_clear()


def angles_of(obj, surface=None, entry=None):
    """(#T,) degrees: the angles of ``obj``'s triangles (style_reach) on ``surface`` (surface_of(obj)).
    Raises SettingsError naming a slot that cannot be built, NativeModuleError, ValueError."""
    coords, triangles, _ = surface_of(obj) if surface is None else surface
    if not np.isfinite(coords).all():
        raise ValueError("'%s' has vertices whose coordinates are not finite numbers" % obj.name)
    gauss_core = native.core()
    for slot in obj.gauss_stylization.styles:
        styles.checked_style(gauss_core, obj, slot)  # a clear message naming the slot, before any use
    check_regions(obj)
    slot_styles = style_reach.slot_styles(gauss_core, obj)
    slots = style_reach.triangle_slots(_face_weights(obj, {} if entry is None else entry))
    return style_reach.triangle_angles(coords, triangles, slots, slot_styles)


def _lifted(coords, triangles):
    """Corner positions (3 #T by 3) a little above the surface, along the area-weighted vertex normals."""
    coords = np.asarray(coords, np.float64)
    normals, areas = directions.triangle_normals(coords, triangles)
    weighted = normals * areas[:, None]
    vertex_normals = np.zeros_like(coords)
    for corner in range(3):
        for axis in range(3):
            vertex_normals[:, axis] += np.bincount(triangles[:, corner], weights=weighted[:, axis],
                                                   minlength=len(coords))
    vertex_normals /= np.maximum(np.linalg.norm(vertex_normals, axis=1), 1e-300)[:, None]
    diagonal = float(np.linalg.norm(coords.max(axis=0) - coords.min(axis=0))) if len(coords) else 0.0
    return (coords + LIFT * diagonal * vertex_normals)[triangles].reshape(-1, 3).astype(np.float32)


def _content_key(obj, surface, stamp):
    """(what the shape is now, everything else the angles depend on). The shape changes continually
    during a run or a drag, and its refresh is throttled; the rest changes at an artist's single action."""
    session = runs.session_of(obj)
    settings = obj.gauss_stylization
    slots = tuple(repr(read_all(styles.STYLE_FIELDS, slot)) + slot.vertex_group for slot in settings.styles)
    coords, triangles = surface[0], surface[1]
    if session is not None:
        shape = ("run", session.steps)
    else:  # the mesh may be changed by any tool: a checksum of its coordinates (NaN compares by its bytes)
        shape = ("mesh", coords.sum(dtype=np.float64).tobytes(), hash(coords[::97].tobytes()))
    rest = (id(session), obj.data.as_pointer(), coords.shape, id(triangles), stamp, slots, settings.method,
            settings.lam, settings.uncovered)
    return shape, rest


def _entry(obj, force=False):
    """The cache entry of ``obj``, its angles computed again if they are out of date and not too recent
    (``force``: however recent)."""
    entry = _cache.setdefault(obj.as_pointer(), {})
    stamp = _stamp(entry, obj)
    surface = surface_of(obj, cached_topology=True, stamp=stamp)
    key = _content_key(obj, surface, stamp)
    if entry.get("key") == key:
        return entry
    now = time.monotonic()
    wait = max(REFRESH_SECONDS, entry.get("cost", 0.0) / REFRESH_SHARE)
    only_moved = entry.get("key") is not None and entry["key"][1] == key[1]
    if not force and only_moved and now - entry.get("time", 0.0) < wait:
        _redraw_later(wait - (now - entry["time"]))
        return entry
    try:
        angles = angles_of(obj, surface, entry)
        positions = _lifted(surface[0], surface[1])
    except (SettingsError, NativeModuleError, ValueError) as exc:
        entry.update(key=key, time=now, cost=0.0, angles=None, positions=None, colours=None, batch=None,
                     problem=str(exc))
        return entry
    entry.update(key=key, time=now, angles=angles, positions=positions, problem=None, batch=None,
                 colours=np.repeat(style_reach.colours(angles, ALPHA), 3, axis=0), cost=time.monotonic() - now)
    return entry


_pending = {"redraw": False}


def _redraw_later(seconds):
    """One redraw of the 3D views after ``seconds``: the change that came too soon after the last
    refresh is shown then."""
    if _pending["redraw"]:
        return
    _pending["redraw"] = True

    def redraw():
        _pending["redraw"] = False
        for window in bpy.context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == 'VIEW_3D':
                    area.tag_redraw()
        return None
    bpy.app.timers.register(redraw, first_interval=max(seconds, 0.01))


def _prune(shown):
    keep = {obj.as_pointer() for obj in shown}
    for pointer in [p for p in _cache if p not in keep]:
        del _cache[pointer]


def draw_surfaces(context):
    """The POST_VIEW handler's body: each shown object's faces in the scale's colours."""
    shown = shown_objects(context)
    _prune(shown)
    gpu.state.blend_set('ALPHA')
    gpu.state.depth_test_set('LESS_EQUAL')
    gpu.state.depth_mask_set(False)
    for obj in shown:
        if obj.mode != 'OBJECT':
            continue
        entry = _entry(obj)
        if entry.get("positions") is None or not len(entry["positions"]):
            continue
        if entry.get("batch") is None:  # uploaded once per change of the angles, not per drawing
            entry["batch"] = gpu_compat.triangles_batch(entry["positions"], entry["colours"])
        gpu.matrix.push()
        gpu.matrix.multiply_matrix(obj.matrix_world)
        gpu_compat.draw_batch(entry["batch"])
        gpu.matrix.pop()
    gpu.state.depth_mask_set(True)


def draw_scale(context):
    """The POST_PIXEL handler's body: the colour scale, and a problem that keeps an object from showing."""
    shown = [obj for obj in shown_objects(context) if obj.mode == 'OBJECT']
    region = context.region
    if not shown or region is None or context.area is None:
        return
    scale = context.preferences.system.ui_scale
    width, height, margin = 160.0 * scale, 10.0 * scale, 20.0 * scale
    visible = viewport.visible_rect(context.area, region)  # clear of a sidebar drawn over the region
    right, bottom = visible.xmax - region.x - margin, visible.ymin - region.y + margin + 16.0 * scale
    left = right - width
    steps = 24
    xs = np.linspace(left, right, steps + 1)
    points = np.array([(x, y) for x in xs for y in (bottom, bottom + height)], np.float32)
    tint = style_reach.colours(np.repeat(np.linspace(0.0, style_reach.SCALE_DEGREES, steps + 1), 2))
    quads = [(2 * i, 2 * i + 1, 2 * i + 3) for i in range(steps)] + [(2 * i, 2 * i + 3, 2 * i + 2) for i in range(steps)]
    gpu.state.blend_set('ALPHA')
    gpu.state.depth_test_set('NONE')
    gpu_compat.draw_triangles(points, tint, quads)
    half = style_reach.SCALE_DEGREES / 2.0
    for text, x in (("0\u00b0", left), ("%g\u00b0" % half, (left + right) / 2.0),
                    ("%g\u00b0+" % style_reach.SCALE_DEGREES, right)):
        _text(text, x, bottom - 13.0 * scale, scale, align="centre")
    _text("Style Reach: angle to the preferred normal", right, bottom + height + 5.0 * scale, scale, align="right")
    line = bottom + height + 20.0 * scale
    for obj in shown:
        problem = _cache.get(obj.as_pointer(), {}).get("problem")
        if problem:
            _text("%s: %s" % (obj.name, problem), right, line, scale, align="right")
            line += 14.0 * scale


def _text(text, x, y, scale, align="left"):
    """``text`` at pixel (x, y) of the region; x is its left end, centre or right end (``align``)."""
    font = 0
    blf.size(font, 11.0 * scale)  # no DPI argument: gone in 4.0
    if align != "left":
        x -= blf.dimensions(font, text)[0] * (0.5 if align == "centre" else 1.0)
    blf.color(font, *TEXT)
    blf.position(font, x, y, 0.0)
    blf.enable(font, blf.SHADOW)
    blf.shadow(font, 3, 0.0, 0.0, 0.0, 0.9)
    blf.shadow_offset(font, 1, -1)
    blf.draw(font, text)
    blf.disable(font, blf.SHADOW)


_surfaces = gpu_compat.ViewDrawHandler("Style Reach overlay", lambda: draw_surfaces(bpy.context), 'POST_VIEW')
_scale = gpu_compat.ViewDrawHandler("Style Reach scale", lambda: draw_scale(bpy.context), 'POST_PIXEL')


def failures():
    """What the two draw handlers raised, each distinct failure once (empty when drawing works)."""
    return _surfaces.failures | _scale.failures


def register():
    _surfaces.add()
    _scale.add()


def unregister():
    _scale.remove()
    _surfaces.remove()
    _cache.clear()
