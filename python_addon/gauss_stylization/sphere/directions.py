"""Face normals as points on the Gauss sphere (numpy only).

What the mesh looks like on the sphere: its triangles' unit normals weighted by
area (what the overlay draws and auto-orient fits), and its dominant directions
(area-weighted clusters of those normals, merged by gauss_core.merge_directions: a
style taken from an example object).
"""

import numpy as np

MIN_SHARE = 0.005          # clusters with less of the total area than this are noise, not a direction
MERGE_DEGREES = 10.0       # normals this close to a cluster's seed belong to that cluster
BIN_DEGREES = 1.0          # normals are first gathered into cells this wide (far finer than a cluster)


def triangle_normals(coords, triangles):
    """Unit normals and areas of triangles.

    coords:    #V by 3 float array
    triangles: #T by 3 int array of vertex indices
    Returns (normals #T by 3 float64, areas #T float64); a zero-area triangle has
    area 0 and normal (0, 0, 0), so weighting by area ignores it.
    """
    # Index first, then widen: the overlay passes a few thousand sampled triangles of a mesh that
    # may have millions of vertices, on every redraw.
    corners = np.asarray(coords)[triangles].astype(np.float64)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    twice_area = np.sqrt(np.einsum("ij,ij->i", cross, cross))
    normals = np.zeros_like(cross)
    np.divide(cross, twice_area[:, None], out=normals, where=twice_area[:, None] > 0)
    return normals, 0.5 * twice_area


def area_sample(areas, count, seed=0):
    """Indices of ``count`` triangles drawn with probability proportional to area (with
    replacement), sorted; all triangles with area if there are no more than ``count``.

    areas: #T float array. The same areas and seed give the same sample (the overlay
    keeps it while the mesh deforms)."""
    areas = np.asarray(areas, np.float64)
    with_area = np.flatnonzero(areas > 0)
    if len(with_area) <= count:
        return with_area
    cumulative = np.cumsum(areas[with_area])
    picks = np.random.default_rng(seed).random(count) * cumulative[-1]
    return with_area[np.minimum(np.searchsorted(cumulative, picks, side="right"), len(with_area) - 1)]


def binned(normals, weights, degrees):
    """Weighted normals gathered into cells about ``degrees`` wide: (directions M by 3,
    summed weights M), the weighted mean direction of each non-empty cell.

    A cheap, order-independent compression of many normals (a bunny's 70K faces) into
    what matters at that resolution; linear in the number of normals. The cells tile
    the six faces of a cube around the sphere (at most 6 * ceil(90 / degrees)^2).
    normals: N by 3 unit vectors; weights: N values > 0.
    """
    normals = np.asarray(normals, np.float64)
    weights = np.asarray(weights, np.float64)
    cells = max(1, int(np.ceil(90.0 / degrees)))
    axis = np.argmax(np.abs(normals), axis=1)
    rows = np.arange(len(normals))
    major = normals[rows, axis]
    side = axis * 2 + (major < 0)
    # The two other coordinates, divided by the major one: a square in [-1, 1]^2 per cube face.
    u = normals[rows, (axis + 1) % 3] / np.abs(major)
    v = normals[rows, (axis + 2) % 3] / np.abs(major)
    iu = np.clip(((u + 1.0) * 0.5 * cells).astype(np.int64), 0, cells - 1)
    iv = np.clip(((v + 1.0) * 0.5 * cells).astype(np.int64), 0, cells - 1)
    cell = (side * cells + iu) * cells + iv
    used, index = np.unique(cell, return_inverse=True)
    sums = np.bincount(index, weights=weights, minlength=len(used))
    mean = np.column_stack([np.bincount(index, weights=weights * normals[:, k], minlength=len(used))
                            for k in range(3)])
    length = np.linalg.norm(mean, axis=1)
    # A cell spans under 90 degrees, so its weighted mean never cancels out.
    return mean / length[:, None], sums


def _with_area(normals, areas):
    """The triangles that have area: (normals, areas, total area), as float64; total is 0 (and the arrays
    empty) when none has, or when the areas do not sum to a positive number."""
    normals = np.asarray(normals, np.float64)
    areas = np.asarray(areas, np.float64)
    used = areas > 0
    total = float(areas[used].sum())
    if not used.any() or not total > 0:
        return np.empty((0, 3)), np.empty(0), 0.0
    return normals[used], areas[used], total


def dominant_directions(gauss_core, normals, areas, max_directions, merge_degrees=MERGE_DEGREES,
                        min_share=MIN_SHARE):
    """The directions most of the surface faces: area-weighted clusters of its normals.

    normals: #T by 3 unit normals; areas: #T areas.
    Returns (directions D by 3, shares D): clusters holding at least ``min_share`` of
    the total area, largest first, at most ``max_directions`` of them; shares sum to at
    most 1. Empty when the surface has no area.
    """
    normals, areas, total = _with_area(normals, areas)
    if total == 0:
        return np.empty((0, 3)), np.empty(0)
    cells, cell_areas = binned(normals, areas, BIN_DEGREES)
    directions, weights = gauss_core.merge_directions(cells, merge_degrees, cell_areas)
    directions, shares = np.asarray(directions), np.asarray(weights) / total
    keep = np.argsort(-shares, kind="stable")
    keep = keep[shares[keep] >= min_share][:max_directions]
    return directions[keep], shares[keep]


def vertex_spread_degrees(num_vertices, triangles, normals, areas):
    """Per vertex: the RMS angle (degrees) of its triangles' normals from their best great circle,
    asin(sqrt(smallest eigenvalue of sum A n n^T / sum A)), 0 where the surface is developable and
    where no triangle with area meets the vertex. triangles: #T by 3; normals: #T by 3 unit; areas: #T."""
    triangles = np.asarray(triangles)
    moment = np.zeros((num_vertices, 3, 3))
    total = np.zeros(num_vertices)
    outer = areas[:, None, None] * normals[:, :, None] * normals[:, None, :]
    for corner in range(3):
        vertices = triangles[:, corner]
        total += np.bincount(vertices, weights=areas, minlength=num_vertices)
        for i in range(3):
            for j in range(i, 3):
                moment[:, i, j] += np.bincount(vertices, weights=outer[:, i, j], minlength=num_vertices)
    moment = np.triu(moment) + np.transpose(np.triu(moment, 1), (0, 2, 1))
    used = total > 0
    smallest = np.zeros(num_vertices)
    smallest[used] = np.linalg.eigvalsh(moment[used] / total[used][:, None, None])[:, 0]
    return np.degrees(np.arcsin(np.sqrt(np.clip(smallest, 0.0, 1.0))))


GAUSS_MAP_CELLS = 4096     # an example's Gauss map is stored as at most this many weighted directions


def gauss_map(normals, areas, max_cells=GAUSS_MAP_CELLS):
    """An example's whole Gauss map, compressed for storage: (directions M by 3, area shares M summing
    to 1), M <= ``max_cells``; empty when the surface has no area.

    The normals are gathered into cells BIN_DEGREES wide (binned), coarser cells (twice as wide each
    time) while there are more than ``max_cells``: a low-poly example keeps every face direction
    exactly (a cube's six), a dense one its distribution at a few degrees.
    """
    normals, areas, total = _with_area(normals, areas)
    if total == 0:
        return np.empty((0, 3)), np.empty(0)
    degrees = BIN_DEGREES
    cells, cell_areas = binned(normals, areas, degrees)
    while len(cells) > max_cells:
        degrees *= 2.0
        cells, cell_areas = binned(normals, areas, degrees)
    return cells, cell_areas / total
