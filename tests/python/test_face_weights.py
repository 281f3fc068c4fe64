"""Painted strength through gauss_core: Solver.set_face_weights, as the add-on uses it with the
weights of its Region groups (float32 from Blender)."""

import numpy as np

import gauss_core
from meshes import icosphere
from measures import aligned_share

CUBE = np.vstack([np.eye(3), -np.eye(3)])


def _solver(V, F, styles, method="gauss"):
    s = gauss_core.Solver(V, F, method=method, acceleration=False)
    s.set_styles(styles)
    return s


def test_one_hot_weights_of_one_are_face_styles_bit_for_bit():
    V, F = icosphere(3)
    styles = [gauss_core.Style.preset("cube"), gauss_core.Style.preset("tetrahedron", mu=2.0)]
    index = np.arange(len(F)) % 3 - 1  # -1, 0, 1
    weights = np.zeros((len(F), 2), np.float32)
    weights[index == 0, 0] = 1
    weights[index == 1, 1] = 1
    for method in ("gauss", "cubic"):
        a, b = _solver(V, F, styles, method), _solver(V, F, styles, method)
        a.set_face_styles(index)
        b.set_face_weights(weights)
        a.step(10)
        b.step(10)
        np.testing.assert_array_equal(a.vertices, b.vertices)


def test_a_gradient_of_weights_gives_a_rising_share_along_it():
    # Four unit spheres in a row along x, weights rising with x from 0 to 1 per vertex (faces: the
    # mean of their vertices'): each sphere along the row ends more cube-aligned than the one before.
    V1, F1 = icosphere(3)
    copies = 4
    V = np.vstack([V1 + [3.0 * i, 0, 0] for i in range(copies)])
    F = np.vstack([F1 + i * len(V1) for i in range(copies)])
    x = V[:, 0]
    vertex_w = ((x - x.min()) / (x.max() - x.min()))[:, None]
    face_w = vertex_w[F, 0].mean(axis=1)[:, None]
    sphere = np.repeat(np.arange(copies), len(F1))
    for method in ("gauss", "cubic"):
        s = _solver(V, F, [gauss_core.Style.preset("cube")], method)
        s.set_face_weights(face_w.astype(np.float32), vertex_w.astype(np.float32))
        s.step(40)
        shares = [aligned_share(s.vertices, F, CUBE, face_mask=sphere == i) for i in range(copies)]
        assert all(later > earlier + 0.01 for earlier, later in zip(shares, shares[1:])), (method, shares)


def test_fewer_columns_than_styles_and_blends():
    V, F = icosphere(3)
    cube = gauss_core.Style.preset("cube")
    two = _solver(V, F, [cube, gauss_core.Style.preset("cube", mu=2.0)])
    two.set_face_weights(np.ones((len(F), 1)))  # the second style weighs 0: cube alone
    one = _solver(V, F, [cube])
    two.step(10)
    one.step(10)
    np.testing.assert_array_equal(two.vertices, one.vertices)
    # A style overlapping itself with weights 1 and 1 counts twice: mu 2.
    blend = _solver(V, F, [cube, cube])
    blend.set_face_weights(np.ones((len(F), 2)))
    blend.step(10)
    np.testing.assert_array_equal(blend.vertices, _stepped(V, F, mu=2.0))


def _stepped(V, F, mu):
    s = _solver(V, F, [gauss_core.Style.preset("cube", mu=mu)])
    s.step(10)
    return s.vertices


def test_face_styles_after_weights_start_over():
    V, F = icosphere(2)
    s = _solver(V, F, [gauss_core.Style.preset("cube")])
    s.set_face_weights(np.full((len(F), 1), 0.25))
    s.set_face_styles(np.zeros(len(F), np.int64))
    s.step(5)
    fresh = _solver(V, F, [gauss_core.Style.preset("cube")])
    fresh.step(5)
    np.testing.assert_array_equal(s.vertices, fresh.vertices)
