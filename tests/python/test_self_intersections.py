"""gauss_core.self_intersections and Solver(avoid_self_intersections=...): a stylization that would pass
through itself does not with the option, as a module user (a script, the add-on) sees it."""
import numpy as np
import pytest

import gauss_core
from conftest import SHARED_MESHES
from meshes import icosphere, read_obj


def _two_spheres(offset):
    V, F = icosphere(2)
    return np.vstack([V, V + [offset, 0, 0]]), np.vstack([F, F + len(V)])


def test_the_crossing_pairs_are_listed_once_in_the_callers_face_numbering():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.3, 0.3, -0.5], [0.3, 0.3, 0.5], [0.35, 0.2, 0.5],
                  [5, 5, 5]], float)
    F = np.array([[6, 6, 6], [0, 1, 2], [3, 4, 5]])  # a face with no area first: skipped, not renumbered
    pairs = gauss_core.self_intersections(V, F)
    assert pairs.dtype == np.int64 and pairs.tolist() == [[1, 2]]
    apart, clean = _two_spheres(3.0), _two_spheres(1.2)
    assert gauss_core.self_intersections(*apart).shape == (0, 2)
    crossing = gauss_core.self_intersections(*clean)
    assert len(crossing) > 20 and (crossing[:, 0] < crossing[:, 1]).all()
    assert len({tuple(p) for p in crossing.tolist()}) == len(crossing)


@pytest.mark.parametrize("V, F, message", [
    (np.array([[0, 0, 0], [1, 0, np.nan], [0, 1, 0]]), np.array([[0, 1, 2]]), "NaN"),
    (np.zeros((3, 3)), np.array([[0, 1, 3]]), "refers to vertex 3"),
    (np.zeros((3, 2)), np.array([[0, 1, 2]]), "V"),
])
def test_bad_input_is_refused_clearly(V, F, message):
    with pytest.raises((ValueError, TypeError), match=message):
        gauss_core.self_intersections(V, F)


def test_the_option_is_a_setting_like_the_others():
    assert gauss_core.DEFAULTS["avoid_self_intersections"] is False
    V, F = icosphere(2)
    solver = gauss_core.Solver(V, F)
    assert solver.avoid_self_intersections is False and solver.held_vertices == 0
    assert len(solver.held_vertex_indices) == 0
    solver.avoid_self_intersections = True
    solver.step(5)
    assert solver.avoid_self_intersections is True
    assert gauss_core.Solver(V, F, avoid_self_intersections=True).avoid_self_intersections is True


def test_spot_under_a_strong_cube_style_stays_clean_with_the_option():
    path = SHARED_MESHES / "small" / "spot_triangulated_2930.obj"
    if not path.exists():
        pytest.skip("../shared/meshes not present")
    V, F = read_obj(path)
    assert len(gauss_core.self_intersections(V, F)) == 0
    results = {}
    for avoid in (False, True):
        solver = gauss_core.Solver(V, F, lam=20.0, avoid_self_intersections=avoid)
        solver.step_until(None, 2000)
        results[avoid] = solver.vertices
        assert np.isfinite(results[avoid]).all()
    assert len(gauss_core.self_intersections(results[False], F)) > 0
    assert len(gauss_core.self_intersections(results[True], F)) == 0


def _cube_share(V, F):
    """Share of faces whose normal lies within 10 degrees of an axis."""
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    return float(np.mean(np.abs(n).max(axis=1) > np.cos(np.radians(10))))


def _two_spheres_askew(offset, levels=3):
    """Two spheres, the second turned and shifted off the first's symmetry planes (mirror images
    meet in degenerate pairs that cross or not by rounding)."""
    V, F = icosphere(levels)
    c, s = np.cos(0.4), np.sin(0.4)
    turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, c, s], [0, -s, c]])
    return np.vstack([V, V @ turn.T + [offset, 0.13, 0.07]]), np.vstack([F, F + len(V)])


@pytest.mark.parametrize("offset", [1.2, 1.7])
def test_a_mesh_that_already_crosses_itself_is_held_only_where_it_crosses(offset):
    # Two spheres pushed into one another: the input crosses itself, as many artists' meshes do. Their
    # crossing may slide on as the surface moves, but no crossing begins elsewhere, and only vertices
    # near the crossing are ever held: the rest stylizes as without the guard (holding every vertex
    # back at some step would freeze the whole mesh).
    V, F = _two_spheres_askew(offset)
    before = gauss_core.self_intersections(V, F)
    assert len(before) > 0
    centroids = V[F].mean(axis=1)
    crossing_faces = np.unique(before)
    shares, held_max = {}, 0
    for avoid in (False, True):
        solver = gauss_core.Solver(V, F, lam=4.0, avoid_self_intersections=avoid)
        for _ in range(300):
            solver.step()
            held_max = max(held_max, solver.held_vertices)
            if solver.converged or solver.held_back:
                break
        result = solver.vertices
        assert np.isfinite(result).all()
        shares[avoid] = _cube_share(result, F)
    after = gauss_core.self_intersections(result, F)
    # Every crossing face at the end lies near the input's crossing (there may be none left: the
    # contact springs can push the spheres' crossing apart).
    gap = np.linalg.norm(centroids[np.unique(after)][:, None] - centroids[crossing_faces][None], axis=2).min(axis=1)
    assert gap.max(initial=0.0) < 0.3, gap.max(initial=0.0)
    assert 0 < held_max < len(V) // 4
    assert shares[True] > shares[False] - 0.03, shares


def test_a_run_the_guard_holds_is_held_back_not_converged():
    # A pinned cap of one sphere dragged into the other: the guard stops the pins short, the run comes to
    # rest there, and says that the guard holds it rather than that it converged.
    V, F = _two_spheres(2.3)
    cap = np.flatnonzero(V[: len(V) // 2, 0] > 0.8)
    targets = V[cap] + [1.0, 0, 0]
    free = gauss_core.Solver(V, F, lam=0.0, pinned=cap)
    free.set_pin_positions(targets)
    free.step_until(1e-3, 500)
    assert free.converged and not free.held_back
    assert len(gauss_core.self_intersections(free.vertices, F)) > 0  # without the guard it passes through
    solver = gauss_core.Solver(V, F, lam=0.0, pinned=cap, avoid_self_intersections=True)
    solver.set_pin_positions(targets)
    taken = solver.step_until(1e-3, 500)
    assert taken < 500 and solver.held_back and not solver.converged
    assert solver.held_vertices > 0
    assert len(gauss_core.self_intersections(solver.vertices, F)) == 0
    # Which vertices (the caller's numbering): on the halves of the spheres that face each other, the
    # pinned cap among them. Not every pin of the cap: all stop short of their targets, but with the
    # contact springs (contact_springs.h) the last step no longer brings every face around them into a
    # new contact.
    held = solver.held_vertex_indices
    assert held.dtype == np.int32 and len(held) == solver.held_vertices
    assert np.all(np.diff(held) > 0) and held.min() >= 0 and held.max() < len(V)
    assert np.isin(cap, held).any()
    first = held < len(V) // 2
    assert np.all(V[held[first], 0] > 0) and np.all(V[held[~first], 0] < 2.3)  # the halves that face each other
    solver.avoid_self_intersections = False  # nothing holds it now: it moves on, and converges
    solver.step_until(1e-3, 500)
    assert solver.converged and not solver.held_back
