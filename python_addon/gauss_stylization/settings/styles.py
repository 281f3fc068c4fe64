"""Style slots -> solver styles, face assignments and pins (pure numpy)."""

import numpy as np

from ..errors import SettingsError
from . import paint_curve, schema
from .fields import Live, Where, check_all
from .schema import CUSTOM, GAUSS_MAP, PIN_THRESHOLD, REGION_THRESHOLD

# What a slot's style (its g) depends on: the fields whose change rebuilds styles.
STYLE_FIELDS = tuple(f for f in schema.SLOT if f.live is Live.STYLES)
_SLOT_NAME = schema.field(schema.OBJECT, "styles").owner_name


def rotation_matrix(slot):
    """The slot's orientation (Euler) as a 3x3 float64 rotation matrix."""
    return np.array(slot.orientation.to_matrix(), dtype=np.float64)


def active_slot(settings):
    """The slot selected in the list (settings.active_style_index), or None."""
    index = settings.active_style_index
    return settings.styles[index] if 0 <= index < len(settings.styles) else None


def make_style(gauss_core, slot, rotation=None, sigma=None):
    """One style slot -> gauss_core.Style (may raise ValueError).

    Every slot field whose change rebuilds styles (Live.STYLES in schema.SLOT) is used here.
    rotation, sigma: instead of the slot's orientation and sigma (auto-orient evaluates the
    unrotated style, and searches with a softer one)."""
    rotation = rotation_matrix(slot) if rotation is None else np.asarray(rotation, np.float64)
    sigma = slot.sigma if sigma is None else sigma
    if slot.preset == CUSTOM:
        # The style turns its normals, as a preset's; the cubic method turns its cube by the same rotation.
        normals = np.array(slot.custom_normal_list(), dtype=np.float64).reshape(-1, 3)
        return gauss_core.Style(normals=normals, rotation=rotation, sigma=sigma, mu=slot.mu)
    if slot.preset == GAUSS_MAP:
        rows = slot.gauss_map_array()
        return gauss_core.Style.gauss_map(rows[:, :3], rows[:, 3], rotation=rotation, sigma=sigma, mu=slot.mu)
    return gauss_core.Style.preset(slot.preset.lower(), sigma=sigma, mu=slot.mu,
                                   rotation=rotation, axis_contribution=slot.axis_contribution)


def checked_style(gauss_core, obj, slot, rotation=None, sigma=None):
    """make_style for one slot of ``obj`` on its own (the sphere overlay, auto-orient): its
    style fields are checked first, and any problem raises SettingsError naming the slot."""
    check_all(STYLE_FIELDS, slot, Where(obj, {}, _SLOT_NAME(slot)))
    try:
        return make_style(gauss_core, slot, rotation, sigma)
    except ValueError as exc:
        raise SettingsError("%s cannot be built: %s" % (_SLOT_NAME(slot), exc)) from exc


def make_styles(gauss_core, slots):
    return [make_style(gauss_core, slot) for slot in slots]


def face_styles(arrays, group_weights, slot_groups, uncovered):
    """Style index of every solver triangle (-1 = unstyled): the assignment before Regions had
    weights (runs use face_weights), kept for scripts.

    A polygon belongs to a slot's region when the weights of its vertices in
    the slot's group average above REGION_THRESHOLD; later slots win overlaps; a slot
    without a group covers the whole mesh. Triangles inherit their polygon's style.
    """
    default = 0 if uncovered == 'FIRST_SLOT' and slot_groups else -1
    polygon_style = np.full(arrays.num_polygons, default, np.int32)
    for index, group in enumerate(slot_groups):
        if not group:
            polygon_style[:] = index
        else:
            inside = arrays.polygon_average(group_weights[group]) > REGION_THRESHOLD
            polygon_style[inside] = index
    return polygon_style[arrays.tri_polygon]


def _filler(slot_groups, uncovered):
    """The slot that takes what the Regions leave, or None. Unstyled (the default): the first slot
    without a Region, none if every slot has one, so a Region on the only slot paints it. First Style
    (files saved before Unstyled was the default keep it, settings/versioning.py): as it always was,
    the last slot without a Region, else the first slot, whose own Region then is whole again."""
    free = [index for index, group in enumerate(slot_groups) if not group]
    if uncovered == 'FIRST_SLOT':
        return free[-1] if free else (0 if slot_groups else None)
    return free[0] if free else None


def _slot_weights(values_of, slot_groups, uncovered, count, steepness):
    """(count, #slots) float32: each slot's weight on ``count`` polygons or vertices.

    values_of(group): the group's weights there ((count,) floats in [0, 1]). A slot with a
    Region weighs its group's weight; where Regions overlap their weights add up. The filler slot
    (_filler) takes what the Regions leave: 1 minus their summed weight, at least 0. Without a
    filler, a face's summed weight says how strongly it is stylized and goes through the paint
    curve of that ``steepness`` (paint_curve.scale_blend)."""
    weights = np.zeros((count, len(slot_groups)), np.float64)
    for index, group in enumerate(slot_groups):
        if group:
            weights[:, index] = values_of(group)
    filler = _filler(slot_groups, uncovered)
    if filler is None:
        weights = paint_curve.scale_blend(weights, steepness)
    else:  # every face is stylized in full: the weights only say how its styles mix
        weights[:, filler] += np.maximum(0.0, 1.0 - weights.sum(axis=1))
    return np.clip(weights, 0.0, 1.0).astype(np.float32)


def region_strength(arrays, vertex_weights):
    """(#polygons,) floats in [0, 1]: a Region's strength on each polygon, from its group's vertex
    weights (0 outside the group). A polygon is in the Region when more than REGION_THRESHOLD of its
    corners carry a weight (the rule Regions always had: with weights of 1 exactly the polygons they
    took before), and its strength is the mean weight of those corners: painting a Region paints its
    strength, and a Region of weights 1 stylizes exactly as before, its edge as crisp."""
    painted = arrays.polygon_average((vertex_weights > 0).astype(np.float64))
    total = arrays.polygon_average(vertex_weights)
    return np.where(painted > REGION_THRESHOLD, total / np.maximum(painted, 1e-30), 0.0)


def face_weights(arrays, group_weights, slot_groups, uncovered, steepness):
    """(#triangles, #slots) float32: each solver triangle's weight for each slot (Solver.set_face_weights).

    A slot's weight on a polygon is its Region's strength there (region_strength; where no slot fills
    the rest, through the paint curve of ``steepness``, paint_curve.steepness_of), which scales the
    slot's mu: painting a Region in Weight Paint mode paints its strength, 0 leaves the polygon to the
    other slots.
    Overlapping Regions blend: the polygon's preference is the weight-scaled sum of its slots'. A
    slot without a Region (or, for Other Faces = First Style, the first slot) takes what the Regions
    leave (see _filler). Triangles inherit their polygon's weights; the cubic method takes each
    vertex's strength from its faces' (no vertex weights), so weights of 1 give exactly the old
    per-vertex strengths there too."""
    polygons = _slot_weights(lambda group: region_strength(arrays, group_weights[group]), slot_groups,
                             uncovered, arrays.num_polygons, steepness)
    return polygons[arrays.tri_polygon]


def pinned_vertices(group_weights, pin_group):
    """Indices (int32) of the vertices held in place (possibly empty)."""
    if not pin_group:
        return np.empty(0, np.int32)
    return np.flatnonzero(group_weights[pin_group] > PIN_THRESHOLD).astype(np.int32)
