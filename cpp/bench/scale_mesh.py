#!/usr/bin/env python3
"""The generated mesh of the scale measurements (numpy only, so Blender's Python imports it too).

A lumpy sphere made from a subdivided cube, n by n quads per side: 6 n^2 + 2 vertices (n = 289:
501,128; n = 409: 1,003,688; n = 580: 2,018,402). scripts/measure_scale.sh measures the solver on it,
tests/blender/measure_blender_scale.py what Blender costs at its size.

usage: scale_mesh.py --n 409 OUT.obj     (writes it as an OBJ, e.g. for tests/blender/measure_tick.py)
"""
import argparse

import numpy as np


def cube_sphere(n):
    """(V, F): (#V,3) float64 and (#F,3) int32 of a closed, consistently oriented sphere from a cube
    with n by n quads per side (6n^2+2 vertices)."""
    u, v = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    keys, faces = [], []
    for axis in range(3):
        for side in (0, n):
            c = np.empty((n + 1, n + 1, 3), np.int64)
            c[..., axis] = side
            c[..., (axis + 1) % 3] = u
            c[..., (axis + 2) % 3] = v
            keys.append((c[..., 0] * (n + 1) + c[..., 1]) * (n + 1) + c[..., 2])
    keys = np.stack(keys)  # (6, n+1, n+1) lattice keys
    unique, index = np.unique(keys.ravel(), return_inverse=True)
    index = index.reshape(keys.shape)
    for f, side in enumerate([0, n] * 3):
        p00, p10 = index[f, :-1, :-1].ravel(), index[f, 1:, :-1].ravel()
        p11, p01 = index[f, 1:, 1:].ravel(), index[f, :-1, 1:].ravel()
        if side == n:
            faces += [np.stack([p00, p10, p11], 1), np.stack([p00, p11, p01], 1)]
        else:
            faces += [np.stack([p00, p11, p10], 1), np.stack([p00, p01, p11], 1)]
    k = unique
    P = np.stack([k // ((n + 1) ** 2), (k // (n + 1)) % (n + 1), k % (n + 1)], 1) * (2.0 / n) - 1.0
    P /= np.linalg.norm(P, axis=1, keepdims=True)
    P *= 1.0 + 0.05 * np.sin(5 * P[:, :1]) * np.cos(3 * P[:, 1:2])  # lumpy, so the style has work to do
    P *= [1.1, 0.9, 0.8]
    return np.ascontiguousarray(P), np.ascontiguousarray(np.concatenate(faces).astype(np.int32))


def write_obj(path, V, F):
    with open(path, "w") as out:
        np.savetxt(out, V, fmt="v %.7g %.7g %.7g")
        np.savetxt(out, F + 1, fmt="f %d %d %d")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=409)
    ap.add_argument("out")
    args = ap.parse_args()
    V, F = cube_sphere(args.n)
    write_obj(args.out, V, F)
    print("%s: %d vertices, %d faces" % (args.out, len(V), len(F)))


if __name__ == "__main__":
    main()
