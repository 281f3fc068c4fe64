"""Example meshes made in code, for styles taken from an example (numpy only, as measures.py)."""
import numpy as np


def icosahedron():
    t = (1.0 + 5.0 ** 0.5) / 2.0
    V = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                  [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], np.float64)
    F = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
                  [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
                  [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]], np.int64)
    return V, F


def decimated(V, F, cells):
    """Vertex clustering: every vertex moves to the mean of its grid cell (``cells`` along the longest
    side); faces that collapse are dropped, as are repeated ones."""
    lo, hi = V.min(axis=0), V.max(axis=0)
    size = (hi - lo).max() / cells
    key = np.floor((V - lo) / size).astype(np.int64)
    _, cluster = np.unique(key, axis=0, return_inverse=True)
    cluster = cluster.ravel()
    count = np.bincount(cluster)
    W = np.column_stack([np.bincount(cluster, weights=V[:, k]) for k in range(3)]) / count[:, None]
    G = cluster[F]
    keep = (G[:, 0] != G[:, 1]) & (G[:, 1] != G[:, 2]) & (G[:, 0] != G[:, 2])
    G = G[keep]
    _, first = np.unique(np.sort(G, axis=1), axis=0, return_index=True)
    return W, G[np.sort(first)]
