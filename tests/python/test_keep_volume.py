"""Keep Volume through gauss_core: Solver.keep_volume."""
import numpy as np
import pytest

import gauss_core
from conftest import SHARED_MESHES
from meshes import icosphere, read_obj


def volume(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0


def area(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return np.linalg.norm(np.cross(b - a, c - a), axis=1).sum() / 2.0


def test_the_watertight_bunny_keeps_its_volume():
    path = SHARED_MESHES / "bunny" / "bunny_watertight_34834.obj"
    if not path.exists():
        pytest.skip("../shared/meshes not present")
    V, F = read_obj(path)
    rest = volume(V, F)
    ratios = {}
    for keep in (False, True):
        s = gauss_core.Solver(V, F, lam=4.0, keep_volume=keep)
        s.step(100)
        ratios[keep] = volume(s.vertices, F) / rest
    assert ratios[False] < 0.9  # measured 0.76
    assert ratios[True] == pytest.approx(1.0, abs=0.01)  # measured 1 - 2e-15


def test_an_open_mesh_keeps_its_area_until_converged():
    V, F = icosphere(3)
    F = F[V[F].mean(axis=1)[:, 2] < 0.3]  # a cap: open
    s = gauss_core.Solver(V, F)
    assert s.keep_volume is False
    s.keep_volume = True
    assert s.keep_volume is True
    assert s.step_until(1e-3, 2000) < 2000
    assert area(s.vertices, F) == pytest.approx(area(V, F), rel=1e-9)
    s.keep_volume = False  # a change of the map: the run is no longer converged
    assert not s.converged


def test_a_pinned_mesh_is_left_alone():
    V, F = icosphere(3)
    kept = gauss_core.Solver(V, F, pinned=[0], keep_volume=True)
    plain = gauss_core.Solver(V, F, pinned=[0])
    kept.step(30)
    plain.step(30)
    np.testing.assert_array_equal(kept.vertices, plain.vertices)
