"""Many custom normals through the module: merge_directions, a 100,000-normal style,
the size limit refused before any copy."""
import time

import numpy as np
import pytest

import gauss_core
from meshes import subdivided_sphere


def random_directions(n, seed=0):
    x = np.random.default_rng(seed).normal(size=(n, 3))
    return x / np.linalg.norm(x, axis=1)[:, None]


def test_merge_directions_weights_and_order_independence():
    D = random_directions(5000)
    area = np.random.default_rng(1).uniform(0.5, 2.0, size=len(D))
    dirs, weights = gauss_core.merge_directions(D, 10.0, weights=area)
    assert dirs.shape == (len(weights), 3) and 0 < len(weights) < len(D)
    assert np.isclose(weights.sum(), area.sum())
    assert np.allclose(np.linalg.norm(dirs, axis=1), 1.0)
    # every input lies within 2 * 10 degrees of its merged direction
    assert (D @ dirs.T).max(axis=1).min() >= np.cos(np.radians(20)) - 1e-12
    perm = np.random.default_rng(2).permutation(len(D))
    dirs2, weights2 = gauss_core.merge_directions(D[perm], 10.0, weights=area[perm])
    assert np.array_equal(dirs, dirs2) and np.array_equal(weights, weights2)
    dirs3, _ = gauss_core.merge_directions(D * 3.0, 10.0, weights=area)  # lengths do not matter
    assert dirs3.shape == dirs.shape and np.allclose(dirs3, dirs)
    counts = gauss_core.merge_directions(np.array([[0, 0, 1], [0, 0, 2], [1, 0, 0]]), 1.0)[1]
    assert sorted(counts) == [1.0, 2.0]


@pytest.mark.parametrize("bad, words", [
    (dict(normals=[[0, 0, 0]], max_angle_degrees=5), "non-zero"),
    (dict(normals=[[0, 0, 1]], max_angle_degrees=91), "between 0 and 90"),
    (dict(normals=[[0, 0, 1]], max_angle_degrees=5, weights=[-1]), ">= 0"),
    (dict(normals=[[0, 0, 1]], max_angle_degrees=5, weights=[1, 2]), "one entry per normal"),
    (dict(normals=[[np.nan, 0, 1]], max_angle_degrees=5), "NaN"),
])
def test_merge_directions_refuses_bad_input(bad, words):
    with pytest.raises(ValueError, match=words):
        gauss_core.merge_directions(**bad)


@pytest.mark.parametrize("sigma", [1e-3, 4.0, 1000.0])
def test_hundred_thousand_normals_set_up_and_stylize(sigma):
    D = random_directions(100_000, seed=3)
    t = time.process_time()
    style = gauss_core.Style(D, sigma=sigma)
    print(f"100,000 normals, sigma {sigma}: set-up {time.process_time() - t:.3f} s CPU")  # measured, not asserted
    assert style.normals.shape == (100_000, 3)
    fit = style.fit
    assert set(fit) == {"nodes", "max_input_error", "tolerance", "truncation_bound"}
    assert 0 < fit["nodes"] < 100_000
    worst = np.abs(style.value(D) - 1.0).max()
    assert worst <= fit["tolerance"] and worst == pytest.approx(fit["max_input_error"], abs=1e-12)
    s = gauss_core.Solver(*_octahedron())
    s.set_styles([style])
    s.step(3)
    assert np.isfinite(s.vertices).all()


def test_presets_and_small_sets_are_summed_exactly():
    assert gauss_core.Style.preset("cube").fit is None
    assert gauss_core.Style(random_directions(64)).fit is None
    assert gauss_core.Style(random_directions(65)).fit is not None


def test_a_meshs_own_face_normals_as_a_style_stylize_it_boundedly():
    V, F = _octahedron()
    V, F = subdivided_sphere(V, F, 3)
    N = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    style = gauss_core.Style(N, sigma=4.0)  # 512 face normals covering the sphere: a plateau
    assert np.abs(style.value(N / np.linalg.norm(N, axis=1)[:, None]) - 1.0).max() <= style.fit["tolerance"]
    s = gauss_core.Solver(V, F)
    s.set_styles([style])
    s.step(20)
    assert np.isfinite(s.vertices).all() and np.abs(s.vertices).max() < 2.0


def test_too_many_normals_are_refused_before_any_copy():
    limit = gauss_core.SIZE_LIMITS["normals"]
    assert limit == 100_000
    with pytest.raises(ValueError, match="merge_directions"):
        gauss_core.Style(random_directions(limit + 1))
    huge = np.broadcast_to(np.array([0.0, 0.0, 1.0]), (10**9, 3))  # 24 GB if it were copied
    with pytest.raises(ValueError, match="at most"):
        gauss_core.Style(huge)


def _octahedron():
    V = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    F = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    return V, F
