"""Measurements shared by the module tests (tests/python) and the add-on tests (tests/blender).

numpy only, so plain Python and Blender's Python both import it.
"""
import importlib.util
import os

import numpy as np


def face_normals(V, F):
    """Unit normals (#F,3) and twice the areas (#F,) of triangles F (#F,3) over vertices V (#V,3)."""
    V = np.asarray(V, np.float64)
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    area = np.linalg.norm(n, axis=1)
    return n / np.maximum(area, 1e-300)[:, None], area


def aligned_share(V, F, directions, degrees=10.0, face_mask=None, rings=()):
    """Area-weighted share of the faces (of those in ``face_mask``, a (#F,) bool array, if given)
    whose normal is within ``degrees`` of one of ``directions`` (#D,3, any length, #D may be 0) or of
    one of ``rings``, (axis, offset) pairs standing for the circles x . axis = offset on the sphere (a
    ring style's preferred normals; the angle to a circle is the difference of polar angles)."""
    n, area = face_normals(V, F)
    d = np.asarray(directions, np.float64).reshape(-1, 3)
    d = d / np.linalg.norm(d, axis=1)[:, None]
    aligned = ((n @ d.T) >= np.cos(np.radians(degrees))).any(axis=1)
    for axis, offset in rings:
        a = np.asarray(axis, np.float64) / np.linalg.norm(axis)
        polar = np.arccos(np.clip(n @ a, -1.0, 1.0))
        aligned |= np.abs(polar - np.arccos(offset)) <= np.radians(degrees)
    if face_mask is not None:
        area, aligned = area[face_mask], aligned[face_mask]
    return float(area[aligned].sum() / area.sum())


# A developable style's faces have no fixed directions to be within 10 degrees of: a face reaches it
# when its corners' normals lie within this many degrees (RMS) of one great circle (what this share
# measures on the corpus: docs/styles.md#sheet-metal).
DEVELOPABLE_DEGREES = 2.0


def _directions():
    """The add-on's sphere/directions.py (numpy only), loaded by path: the spread is the add-on's
    Style Reach measure, written once."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python_addon",
                        "gauss_stylization", "sphere", "directions.py")
    spec = importlib.util.spec_from_file_location("gauss_directions", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def developable_share(V, F, degrees=DEVELOPABLE_DEGREES, face_mask=None):
    """Area-weighted share of the faces (of those in ``face_mask``) whose three corners each have their
    normals within ``degrees`` of one great circle: where a developable style is reached."""
    F = np.asarray(F)
    n, area = face_normals(V, F)
    reached = _directions().vertex_spread_degrees(len(V), F, n, area)[F].max(axis=1) <= degrees
    if face_mask is not None:
        area, reached = area[face_mask], reached[face_mask]
    return float(area[reached].sum() / max(area.sum(), 1e-300))


def style_share(V, F, style, degrees=10.0, face_mask=None):
    """aligned_share against a gauss_core.Style's preferred normals and rings; for a developable style
    (Sheet Metal), developable_share."""
    if getattr(style, "kind", "directions") == "developable":
        return developable_share(V, F, face_mask=face_mask)
    rings = [(style.axis, offset) for offset in style.ring_offsets]
    return aligned_share(V, F, style.normals, degrees, face_mask, rings)


def developability(V, F):
    """Mean over the vertices faces use of the smallest eigenvalue of sum A n n^T / sum A over the
    vertex's faces: 0 where the normals around a vertex lie on one great circle (a developable
    surface), up to 1/3. The same measure as cpp/include/gauss/mesh/developability.h."""
    F = np.asarray(F)
    n, area = face_normals(V, F)
    keep = area > 0
    n, area, F = n[keep], area[keep], F[keep]
    nV = len(V)
    moment = np.zeros((nV, 3, 3))
    total = np.zeros(nV)
    nn = area[:, None, None] * n[:, :, None] * n[:, None, :]
    for k in range(3):
        np.add.at(moment, F[:, k], nn)
        np.add.at(total, F[:, k], area)
    used = total > 0
    smallest = np.linalg.eigvalsh(moment[used] / total[used][:, None, None])[:, 0]
    return float(np.maximum(smallest, 0.0).mean())


def squareness(V, F, up=(0.0, 0.0, 1.0), degrees=10.0):
    """Area of the faces within ``degrees`` of ``up`` over the area of the smallest square (any
    orientation about ``up``) holding their vertices: 1 for a square cap, pi/4 for a round one, 0 when
    no face faces up. The same measure as cpp/include/gauss/mesh/squareness.h."""
    F = np.asarray(F)
    n, twice_area = face_normals(V, F)
    up = np.asarray(up, np.float64) / np.linalg.norm(up)
    facing = (twice_area > 0) & (n @ up >= np.cos(np.radians(degrees)))
    if not facing.any():
        return 0.0
    a = np.array([1.0, 0.0, 0.0]) if abs(up[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = a - a.dot(up) * up
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(up, e1)
    P = np.asarray(V, np.float64)[np.unique(F[facing])]
    p = np.stack([P @ e1, P @ e2], axis=1)
    t = np.radians(np.arange(900) * 0.1)
    x = p @ np.stack([np.cos(t), np.sin(t)])  # (#P, 900): coordinates along each orientation's axes
    y = p @ np.stack([-np.sin(t), np.cos(t)])
    side = np.maximum(np.ptp(x, axis=0), np.ptp(y, axis=0)).min()
    return float(0.5 * twice_area[facing].sum() / side ** 2) if side > 0 else 0.0


def fibonacci_lattice(count):
    """(count, 3) unit vectors spread evenly over the sphere (the Fibonacci lattice): the cells of the
    Gauss-map histograms below, each about 4 pi / count steradians."""
    i = np.arange(count, dtype=np.float64) + 0.5
    z = 1.0 - 2.0 * i / count
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    phi = np.pi * (3.0 - np.sqrt(5.0)) * i
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def gauss_histogram(normals, areas, lattice):
    """Area-weighted histogram of unit ``normals`` (#N, 3) with ``areas`` (#N,) on the cells of
    ``lattice`` (#L, 3): each normal counts for the cell whose centre is nearest; (#L,) shares summing
    to 1."""
    normals = np.asarray(normals, np.float64)
    areas = np.asarray(areas, np.float64)
    keep = areas > 0
    cell = np.argmax(normals[keep] @ np.asarray(lattice).T, axis=1)
    hist = np.bincount(cell, weights=areas[keep], minlength=len(lattice))
    return hist / hist.sum()


def mesh_gauss_histogram(V, F, lattice):
    """gauss_histogram of a mesh's face normals weighted by area."""
    n, area = face_normals(V, F)
    return gauss_histogram(n, area, lattice)


def _logsumexp(m, axis):
    top = m.max(axis=axis, keepdims=True)
    return (top + np.log(np.exp(m - top).sum(axis=axis, keepdims=True))).squeeze(axis)


def sphere_emd(a, b, lattice, epsilon=0.01, iterations=20000, tolerance=1e-10):
    """Earth mover's distance, in radians, between two histograms ``a`` and ``b`` (#L, shares summing
    to 1) on the cells of ``lattice`` (#L, 3), the ground metric being the angle between cell centres:
    the least mean angle the mass of ``a`` must turn through to become ``b``. 0 for equal histograms,
    at most pi.

    Computed by log-domain Sinkhorn iterations with entropy weight ``epsilon`` (radians) on the cells
    either histogram uses, then rounded to a plan with exactly the marginals a and b (Altschuler, Weed
    and Rigollet 2017) whose cost is returned: a true transport cost, so never below the exact EMD, and
    above it by at most about epsilon * log(#cells) (docs/styles.md#gauss-map says by how much in
    practice)."""
    a = np.asarray(a, np.float64)
    b = np.asarray(b, np.float64)
    ia, ib = np.flatnonzero(a > 0), np.flatnonzero(b > 0)
    pa, pb = a[ia] / a[ia].sum(), b[ib] / b[ib].sum()
    L = np.asarray(lattice, np.float64)
    C = np.arccos(np.clip(L[ia] @ L[ib].T, -1.0, 1.0))
    log_a, log_b = np.log(pa), np.log(pb)
    f, g = np.zeros(len(ia)), np.zeros(len(ib))
    for step in range(iterations):
        f = epsilon * (log_a - _logsumexp((g[None, :] - C) / epsilon, axis=1))
        g = epsilon * (log_b - _logsumexp((f[:, None] - C) / epsilon, axis=0))
        if step % 20 == 19 and np.abs(np.exp(f / epsilon + _logsumexp((g[None, :] - C) / epsilon, axis=1))
                                      - pa).sum() < tolerance:
            break
    plan = np.exp((f[:, None] + g[None, :] - C) / epsilon)
    # Rounding: scale rows and columns down to their marginals, then add the missing mass as a product.
    plan *= np.minimum(1.0, pa / np.maximum(plan.sum(axis=1), 1e-300))[:, None]
    plan *= np.minimum(1.0, pb / np.maximum(plan.sum(axis=0), 1e-300))[None, :]
    ra, rb = pa - plan.sum(axis=1), pb - plan.sum(axis=0)
    if ra.sum() > 0:
        plan += np.outer(ra, rb) / ra.sum()
    return float((plan * C).sum())
