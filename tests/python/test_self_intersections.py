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
