"""Where the style is not reached: each face's angle to the normal its style prefers for it.

A face of a style with directions (every preset but Sheet Metal, and Custom) is measured against its
style's nearest preferred normal or ring; a face of Sheet Metal, which has no fixed directions, by how
far the normals around it spread from one great circle (the RMS angle of the normals around each of its
corners from their best great circle, the largest of the three: 0 where the surface is developable);
a face of a Gauss Map style (an example's whole distribution of normals) against the example's nearest
face direction; a face no slot stylizes has no angle (NaN).
Each triangle takes the slot with the largest weight on it, as the solver's blend is led by it. The
Cubic method's slots prefer the axes of their rotated cube. Pure numpy; the overlay and the
operators read the mesh and draw.
"""

import numpy as np

from ..settings import schema, styles
from . import directions

SCALE_DEGREES = schema.REACH_SCALE_DEGREES
_GREEN, _YELLOW, _RED = np.array([0.15, 0.75, 0.3]), np.array([0.95, 0.85, 0.2]), np.array([0.9, 0.2, 0.15])
UNSTYLED = (0.55, 0.55, 0.55)
_MAX_PRODUCTS = 4_000_000  # triangle-normal products per chunk: a Custom style may have 100,000 normals


def slot_styles(gauss_core, obj):
    """The gauss_core.Style each slot of ``obj`` is measured against (the Cubic method: its cube)."""
    settings = obj.gauss_stylization
    if schema.is_cubic(settings):
        return [gauss_core.Style.preset("cube", rotation=styles.rotation_matrix(slot)) for slot in settings.styles]
    return styles.make_styles(gauss_core, settings.styles)


def triangle_slots(face_weights):
    """(#T,) int: the slot with the largest weight on each triangle, -1 where every weight is 0.
    face_weights: (#T, #slots), as Solver.set_face_weights takes them."""
    weights = np.asarray(face_weights)
    if weights.shape[1] == 0:
        return np.full(len(weights), -1)
    leading = np.argmax(weights, axis=1)
    return np.where(weights.max(axis=1) > 0, leading, -1)


def _direction_angles(normals, style):
    """Degrees from each unit normal (N by 3) to the style's nearest preferred normal or ring."""
    best = np.full(len(normals), np.pi)
    preferred = np.asarray(style.normals, np.float64).reshape(-1, 3)
    if len(style.ring_offsets) and style.axis_contribution <= 0.0:
        preferred = preferred[:0]  # a ring preset's axis normals weigh nothing then (Axis Weight 0)
    if len(preferred):
        preferred = preferred / np.linalg.norm(preferred, axis=1)[:, None]
        chunk = max(1, _MAX_PRODUCTS // len(preferred))
        for start in range(0, len(normals), chunk):
            cosines = normals[start:start + chunk] @ preferred.T
            best[start:start + chunk] = np.arccos(np.clip(cosines.max(axis=1), -1.0, 1.0))
    if len(style.ring_offsets):
        axis = np.asarray(style.axis, np.float64)
        polar = np.arccos(np.clip(normals @ (axis / np.linalg.norm(axis)), -1.0, 1.0))
        for offset in style.ring_offsets:
            best = np.minimum(best, np.abs(polar - np.arccos(np.clip(offset, -1.0, 1.0))))
    return np.degrees(best)


def triangle_angles(coords, triangles, slot_of_triangle, slot_styles_):
    """(#T,) degrees: each triangle's angle to what its slot's style prefers for it (see the module's
    docstring); NaN for a triangle no slot stylizes or without area."""
    normals, areas = directions.triangle_normals(coords, triangles)
    angles = np.full(len(triangles), np.nan)
    spread = None
    for index, style in enumerate(slot_styles_):
        mine = (slot_of_triangle == index) & (areas > 0)
        if not mine.any():
            continue
        if style.kind == "developable":
            if spread is None:
                spread = directions.vertex_spread_degrees(len(coords), triangles, normals, areas)
            angles[mine] = spread[triangles[mine]].max(axis=1)
        elif style.kind in ("directions", "gauss_map"):  # a Gauss Map's normals: the example's directions
            angles[mine] = _direction_angles(normals[mine], style)
        else:
            raise ValueError("Style Reach cannot measure a style of kind '%s'" % style.kind)
    return angles


def polygon_angles(triangle_angles_, areas, tri_polygon, num_polygons):
    """(#P,) degrees: the area-weighted mean of each polygon's triangles' angles (NaN if none has one)."""
    known = np.isfinite(triangle_angles_) & (areas > 0)
    weight = np.where(known, areas, 0.0)
    sums = np.bincount(tri_polygon, weights=np.where(known, triangle_angles_, 0.0) * weight, minlength=num_polygons)
    totals = np.bincount(tri_polygon, weights=weight, minlength=num_polygons)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(totals > 0, sums / totals, np.nan)


def colours(angles, alpha=1.0):
    """(N, 4) float32 colours of the scale: green at 0 degrees, yellow at half SCALE_DEGREES, red from
    SCALE_DEGREES on; grey (UNSTYLED) where the angle is NaN."""
    t = np.clip(np.nan_to_num(np.asarray(angles, np.float64), nan=0.0) / SCALE_DEGREES, 0.0, 1.0)[:, None]
    low = _GREEN + (_YELLOW - _GREEN) * np.minimum(t * 2.0, 1.0)
    rgb = np.where(t < 0.5, low, _YELLOW + (_RED - _YELLOW) * (t * 2.0 - 1.0))
    rgb[~np.isfinite(np.asarray(angles, np.float64))] = UNSTYLED
    return np.column_stack([rgb, np.full(len(rgb), alpha)]).astype(np.float32)
