"""One cell of the quality matrix: an option (options.py) run on one mesh, and what it records.

The run steps until reldV < TOLERANCE (stopped; `converged` is what the solver says of it) or
STEP_CAP steps, one step at a time, so that the vertices the
guard held back and each step's time are seen after every step: its wall time, and the CPU time of
the process's threads, which a busy machine inflates less. Errors the module raises on bad input
are recorded, not raised: a broken mesh must give a clean error or a result. A run the solver calls
converged while the guard held vertices in its last step takes one more step without the guard, which
must stay below the tolerance too (unguarded_still).
"""
import importlib.util
import os
import statistics
import time

import numpy as np

import gauss_core
from measures import face_normals, style_share

def paint_curve():
    """The add-on's paint curve (settings/paint_curve.py, numpy only), loaded by path."""
    path = os.path.join(os.path.dirname(__file__), "..", "..", "python_addon", "gauss_stylization", "settings",
                        "paint_curve.py")
    spec = importlib.util.spec_from_file_location("paint_curve", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


TOLERANCE = 1e-3
STEP_CAP = 400
BOUND = 2.0  # a result is bounded when it stays within BOUND input bounding-box diagonals of its centre


def crossing_pairs(V, F):
    """The set of face pairs that pass through each other, as Blender's 3D-Print toolbox counts them."""
    return {tuple(p) for p in gauss_core.self_intersections(V, F).tolist()}


def slid_from_input_crossings(F, pairs_in, pairs):
    """How many of `pairs` (new crossing pairs) lie in a crossing region that holds one of the input's
    crossing pairs: the regions are the faces of `pairs_in` and `pairs`, joined where two share a corner
    or cross each other. The guard lets a crossing the input had slide on to the faces around it, step
    after step (self_intersection.h), so the region may move and grow; a pair in a region of its own is
    a crossing that began somewhere else, which the guard never allows."""
    if not pairs or not pairs_in:
        return 0
    faces = sorted({f for pair in pairs_in | set(pairs) for f in pair})
    parent = {f: f for f in faces}

    def root(f):
        while parent[f] != f:
            parent[f] = parent[parent[f]]
            f = parent[f]
        return f

    first_face_at = {}
    for f in faces:
        for v in F[f].tolist():
            if v in first_face_at:
                parent[root(f)] = root(first_face_at[v])
            else:
                first_face_at[v] = f
    for f, g in pairs_in | set(pairs):
        parent[root(f)] = root(g)
    seeded = {root(f) for pair in pairs_in for f in pair}
    return sum(1 for f, _g in pairs if root(f) in seeded)


def mesh_kind(V, F):
    """'broken' (a face without area, an edge of more than two faces), 'boundary' (an edge of one face)
    or 'closed'."""
    _, area = face_normals(V, F)
    diagonal = np.linalg.norm(V.max(axis=0) - V.min(axis=0)) if len(V) else 0.0
    edges = np.sort(F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, uses = np.unique(edges, axis=0, return_counts=True)
    if (area <= 1e-12 * diagonal ** 2).any() or (uses > 2).any():
        return "broken"
    return "boundary" if (uses == 1).any() else "closed"


def _style(option):
    if option.sigma is None:
        return gauss_core.Style.preset(option.preset)
    return gauss_core.Style.preset(option.preset, sigma=option.sigma)


def _bounded(V, W):
    low, high = V.min(axis=0), V.max(axis=0)
    diagonal = max(float(np.linalg.norm(high - low)), 1e-300)
    return bool(np.linalg.norm(W - (low + high) / 2, axis=1).max() <= BOUND * diagonal)


def run_option(option, V, F, pairs_in):
    """The record (a dict of plain values) of `option` on the mesh (V, F) whose input crossing pairs are
    `pairs_in`."""
    record = {"option": option.name, "pairs_in": len(pairs_in)}
    style = _style(option)
    try:
        keywords = dict(option.keywords, method=option.method, tolerance=TOLERANCE)
        if option.lam is not None:
            keywords["lam"] = option.lam
        elif option.preset in gauss_core.PRESET_LAMBDA:  # a preset with a lambda of its own (Sheet Metal)
            keywords["lam"] = gauss_core.PRESET_LAMBDA[option.preset]
        pins = option.pins(V, F) if option.pins else None
        start = time.perf_counter()
        solver = gauss_core.Solver(V, F, pinned=pins, **keywords)
        record["setup_s"] = time.perf_counter() - start
        solver.set_styles([style])
        weights = option.weights(V, F) if option.weights else None
        if weights is not None:  # through the add-on's paint curve, as a painted Region's weights go
            curve = paint_curve()
            independent = keywords.get("resolution_independent", gauss_core.DEFAULTS["resolution_independent"])
            k = curve.steepness(option.method.upper(), keywords.get("lam", gauss_core.DEFAULTS["lam"]),
                                curve.pull_shown(independent))
            solver.set_face_weights(curve.scale_blend(weights, k))
        step_ms, cpu_ms, held = [], [], []
        while len(step_ms) < STEP_CAP and not solver.last_reldv < TOLERANCE:
            start, cpu = time.perf_counter(), time.process_time()
            solver.step()
            step_ms.append(1e3 * (time.perf_counter() - start))
            cpu_ms.append(1e3 * (time.process_time() - cpu))
            held.append(solver.held_vertices)
        W = solver.vertices
    except (ValueError, TypeError, MemoryError) as error:  # the module's clean refusals
        record["error"] = f"{type(error).__name__}: {error}"
        return record
    finite = bool(np.isfinite(W).all())
    record.update(
        steps=len(step_ms), stopped=bool(solver.last_reldv < TOLERANCE), converged=bool(solver.converged),
        held_back=bool(solver.held_back), runaway=solver.runaway_steps,
        held_max=max(held, default=0),
        held_last=held[-1] if held else 0, ms_per_step=statistics.median(step_ms) if step_ms else 0.0,
        cpu_ms_per_step=statistics.median(cpu_ms) if cpu_ms else 0.0,
        finite=finite, bounded=finite and _bounded(V, W),
        share_in=style_share(V, F, style), share=style_share(W, F, style) if finite else None)
    if record["converged"] and record["held_last"]:
        # The solver says converged although the guard held vertices in the last step (what it held was
        # too little to matter): one more step without the guard checks that claim.
        solver.avoid_self_intersections = False
        solver.step()
        record["unguarded_reldv"] = float(solver.last_reldv)
        record["unguarded_still"] = bool(solver.last_reldv < TOLERANCE)
    if finite:
        pairs_out = crossing_pairs(W, F)
        new = pairs_out - pairs_in
        record.update(pairs_out=len(pairs_out), new_pairs=len(new),
                      new_pairs_sliding=slid_from_input_crossings(F, pairs_in, new))
    if weights is not None and len(weights) and (weights == weights[0, 0]).all():
        record["uniform_weight"] = float(weights[0, 0])
    if weights is not None and finite and (weights <= 0.2).any() and (weights >= 0.8).any():
        record["share_light"] = style_share(W, F, style, face_mask=weights[:, 0] <= 0.2)
        record["share_heavy"] = style_share(W, F, style, face_mask=weights[:, 0] >= 0.8)
    return record
