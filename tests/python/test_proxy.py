"""gauss_core.Proxy: a simplified copy of a large mesh, and its deformation carried back to the mesh."""
import numpy as np
import pytest

import gauss_core
from measures import style_share
from meshes import icosphere


@pytest.fixture(scope="module")
def sphere():
    V, F = icosphere(4)  # 2,562 vertices
    V = V * [1.2, 1.0, 0.8]  # an ellipsoid, so that the proxy has curvature to keep
    return V, F


@pytest.fixture(scope="module")
def proxy(sphere):
    return gauss_core.Proxy(*sphere, target_vertices=500)


def test_the_proxy_is_made_of_the_mesh_own_vertices(sphere, proxy):
    V, F = sphere
    P, G = proxy.vertices, proxy.triangles
    assert P.shape == (len(proxy.fine_of_proxy), 3) and P.dtype == np.float64
    assert 450 <= len(P) <= 500
    assert G.dtype == np.int32 and G.min() >= 0 and G.max() < len(P)
    assert np.array_equal(P, V[proxy.fine_of_proxy])
    face, bary, offset = proxy.fine_map
    assert face.shape == (len(V),) and bary.shape == (len(V), 2) and offset.shape == (len(V), 3)
    assert proxy.num_fine_vertices == len(V)
    assert (face >= 0).all() and (face < len(G)).all()
    # Every vertex lies close to the proxy: on average within 0.3% of the size, at most 2%.
    size = np.ptp(V, axis=0).max()
    distance = np.linalg.norm(offset, axis=1)
    assert distance.mean() < 0.003 * size and distance.max() < 0.02 * size


def test_transfer_of_the_rest_shape_and_of_a_rigid_motion(sphere, proxy):
    V, _ = sphere
    out = np.empty((len(V), 3), np.float32)
    proxy.transfer(proxy.vertices, out)
    assert np.abs(out - V).max() < 1e-6
    angle = 0.7
    R = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    moved = (proxy.vertices @ R.T + [1, 2, 3]).astype(np.float32)  # float32, as vertices_into gives it
    flat = np.empty(3 * len(V), np.float32)
    proxy.transfer(moved, flat)
    assert np.abs(flat.reshape(-1, 3) - (V @ R.T + [1, 2, 3])).max() < 1e-5


def test_bad_arguments_are_refused(sphere, proxy):
    V, F = sphere
    out = np.empty((len(V), 3), np.float32)
    with pytest.raises(ValueError):
        proxy.transfer(proxy.vertices[:-1], out)
    with pytest.raises(ValueError):
        proxy.transfer(proxy.vertices, out[:-1])
    with pytest.raises(TypeError):
        proxy.transfer(proxy.vertices, np.empty((len(V), 3), np.float64))
    with pytest.raises(ValueError):
        proxy.transfer(proxy.vertices, np.empty((3, len(V)), np.float32).T)  # not C-contiguous
    with pytest.raises(TypeError):
        proxy.transfer(proxy.vertices.astype(np.int32), out)
    with pytest.raises(ValueError):
        gauss_core.Proxy(V, F, target_vertices=3)
    bad = V.copy()
    bad[5, 1] = np.nan
    with pytest.raises(ValueError, match="vertex 5"):
        gauss_core.Proxy(bad, F, target_vertices=100)
    with pytest.raises(ValueError, match="refers to vertex"):
        gauss_core.Proxy(V, np.where(F == 0, len(V), F), target_vertices=100)


def _stylized(V, F, start=None):
    """A run of the cube style at lambda 4 until reldV < 1e-5 (far enough that where it stops does not
    depend on how fast it got there) from ``start``: its vertices."""
    solver = gauss_core.Solver(V, F, lam=4.0, tolerance=1e-5)
    solver.set_styles([gauss_core.Style.preset("cube")])
    if start is not None:
        solver.set_vertices(start)
    solver.step_until(None, 3000)
    return solver.vertices


@pytest.mark.parametrize("target, within", [(1200, 0.003), (500, None)])
def test_a_stylized_proxy_warm_starts_the_full_mesh(sphere, target, within):
    """The live run's path at a small size: stylize the proxy, carry it to the mesh, finish with steps on
    the mesh. It takes the style as a run on the mesh from scratch does (the share within 0.02). On a
    proxy of half the vertices it also ends at the same shape (within 0.3% of the diagonal on average);
    on one of a fifth it ends at another, as stylized, about 1.2% away (docs/performance.md#sculpt-scale)."""
    V, F = sphere
    proxy = gauss_core.Proxy(V, F, target_vertices=target)
    out = np.empty((len(V), 3), np.float32)
    proxy.transfer(_stylized(proxy.vertices, proxy.triangles), out)
    warm, scratch = _stylized(V, F, out), _stylized(V, F)
    cube = gauss_core.Style.preset("cube")
    shares = [style_share(x, F, cube) for x in (scratch, warm)]
    assert abs(shares[0] - shares[1]) <= 0.02, shares
    assert shares[0] > style_share(V, F, cube) + 0.3  # the style took: a share to compare
    if within is not None:
        distance = np.linalg.norm(warm - scratch, axis=1).mean() / np.linalg.norm(np.ptp(V, axis=0))
        assert distance <= within, distance
