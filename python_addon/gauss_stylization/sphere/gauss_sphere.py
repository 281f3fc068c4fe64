"""The Gauss sphere as the viewport shows it (numpy only): where it sits in a 3D view,
how directions map to pixels and back, its triangles and their heat-map colours.

The sphere turns with the view like Blender's navigation gizmo: a direction d of
the object (object space) is seen at view = V d, with V = the view's rotation times
the object's rotation, and drawn at centre + radius * (view.x, view.y); the half
with view.z > 0 faces the viewer. Pixels are region pixels (origin bottom left).
"""

from collections import namedtuple

import numpy as np

RADIUS_PX = 80.0           # sphere radius at UI scale 1 ...
MAX_RADIUS_SHARE = 0.22    # ... but at most this share of the region's smaller side
MARGIN_PX = 24.0           # from the region's bottom-left corner (past the toolbar)
SUBDIVISIONS = 4           # icosphere levels: 2562 vertices, about 4 degrees apart

# Heat map of g from 0 (dark violet) to 1 (pale yellow): position, RGB.
# Most of the contrast is near 1, where faces are pulled towards (at sigma 4 g stays above
# about 0.5 for the cube).
HEAT_STOPS = np.array([0.0, 0.45, 0.7, 0.88, 1.0])
HEAT_COLOURS = np.array([[0.04, 0.03, 0.18], [0.35, 0.06, 0.45], [0.80, 0.18, 0.25],
                         [0.97, 0.60, 0.15], [1.00, 0.97, 0.62]])

Frame = namedtuple("Frame", "x y radius")  # the sphere's centre and radius in region pixels


def frame(region_width, region_height, left_inset=0.0, ui_scale=1.0):
    """Where the sphere is drawn in a region of that size: its bottom-left corner, right of
    ``left_inset`` pixels (a toolbar drawn over the region), out of the mesh's way."""
    radius = min(RADIUS_PX * ui_scale, MAX_RADIUS_SHARE * min(region_width, region_height))
    margin = MARGIN_PX * ui_scale
    return Frame(left_inset + margin + radius, margin + radius, radius)


def to_pixels(view_directions, where):
    """Pixels (N by 2) of view-space unit directions (N by 3) on the sphere at ``where``."""
    return np.column_stack([where.x + where.radius * view_directions[:, 0],
                            where.y + where.radius * view_directions[:, 1]])


def from_pixel(x, y, where):
    """The view-space unit direction (3,) seen at pixel (x, y) and whether the pixel is on
    the sphere; off the sphere it is the nearest direction on its rim."""
    u, v = (x - where.x) / where.radius, (y - where.y) / where.radius
    squared = u * u + v * v
    if squared <= 1.0:
        return np.array([u, v, np.sqrt(1.0 - squared)]), True
    length = np.sqrt(squared)
    return np.array([u / length, v / length, 0.0]), False


def subdivided_sphere(vertices, faces, levels):
    """Split every triangle in four ``levels`` times, pushing new vertices onto the unit sphere.

    vertices: V by 3 (made unit length), faces: F by 3 outward triangles.
    Returns (vertices #V by 3 float64, faces #F by 3 int64). (tests/python/meshes.py uses it too.)"""
    vertices = [np.asarray(v, float) / np.linalg.norm(v) for v in vertices]
    faces = [tuple(f) for f in faces]
    for _ in range(levels):
        middle = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                point = vertices[a] + vertices[b]
                vertices.append(point / np.linalg.norm(point))
                middle[key] = len(vertices) - 1
            return middle[key]

        finer = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = finer
    return np.array(vertices), np.array(faces, np.int64)


def icosphere(levels=SUBDIVISIONS):
    """Unit vertices (N by 3) and outward triangles (M by 3) of a subdivided icosahedron."""
    t = (1.0 + np.sqrt(5.0)) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    return subdivided_sphere(vertices, faces, levels)


def heat_colours(values):
    """RGBA (N by 4) of g values: 0 and below darkest, 1 and above brightest."""
    t = np.clip(np.asarray(values, np.float64), 0.0, 1.0)
    rgb = np.column_stack([np.interp(t, HEAT_STOPS, HEAT_COLOURS[:, k]) for k in range(3)])
    return np.column_stack([rgb, np.ones(len(t))])


def shaded(colours, view_directions):
    """Colours darkened towards the rim, so the disc reads as a ball."""
    light = 0.45 + 0.55 * np.clip(view_directions[:, 2], 0.0, 1.0)
    out = colours.copy()
    out[:, :3] *= light[:, None]
    return out


def facing(view_directions, triangles):
    """Triangles whose centre is on the half of the sphere that faces the viewer (the
    back half would be drawn over it: there is no depth test in 2D)."""
    return triangles[view_directions[triangles, 2].sum(axis=1) > 0.0]


AXIS_LABEL_REACH = 1.18  # axis labels sit this many radii from the centre along the axis, seen from the view


def axis_labels(turn, where):
    """Where the object's axes X, Y, Z are labelled around the sphere at ``where``: [(name, x, y,
    facing)], x and y the label's centre in region pixels, ``facing`` True when the axis points
    towards the viewer. turn: V (3 by 3) of the module docstring. An axis in the view's plane is
    labelled just outside the rim, one pointing at the viewer nearer the centre (as Blender's
    navigation gizmo does)."""
    labels = []
    for index, name in enumerate("XYZ"):
        seen = np.asarray(turn, np.float64)[:, index]
        x, y = to_pixels(AXIS_LABEL_REACH * seen[None], where)[0]
        labels.append((name, float(x), float(y), bool(seen[2] >= 0.0)))
    return labels


def disc(where, segments=96, grow=1.0):
    """Triangles (segments * 3 by 2 pixels) filling the sphere's outline, ``grow`` times its radius."""
    angles = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    rim = np.column_stack([where.x + grow * where.radius * np.cos(angles),
                           where.y + grow * where.radius * np.sin(angles)])
    centre = np.array([where.x, where.y])
    return np.stack([np.broadcast_to(centre, (segments, 2)), rim[:-1], rim[1:]], axis=1).reshape(-1, 2)
