#!/usr/bin/env python3
"""Midpoint subdivision of a triangle mesh: the same surface, tessellated finer.

usage: python3 scripts/subdivide_mesh.py MESH.obj OUT_DIR [--levels 1 2]

Writes OUT_DIR/<name>_sub<L>.obj for each level L: every triangle split into four by its edge
midpoints, L times. The new vertices lie on the old triangles, so the surface (and its bounding box)
does not change, and the original vertices keep their numbers 0..n-1 (new ones follow), which is
what the resolution measurements compare (docs/resolution.md). The outputs are measuring
material, not test meshes: write them to a temporary or out/ folder, never into the repository.
numpy only; midpoint_subdivide() is imported by cpp/bench/measure_resolution.py and the tests.
"""
import argparse
import pathlib
import sys

import numpy as np

# The OBJ reader the tests and the quality matrix share.
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests" / "common"))
from mesh_files import read_obj  # noqa: E402  (re-exported: the measure scripts import it from here)


def midpoint_subdivide(V, F, levels=1):
    """(V', F') after `levels` rounds of splitting each triangle of F (#F,3) into four.
    V' starts with V (#V,3) unchanged; each edge's midpoint is added once, shared by its faces."""
    V = np.asarray(V, np.float64)
    F = np.asarray(F, np.int64)
    for _ in range(levels):
        corners = [F[:, 0], F[:, 1], F[:, 2]]
        halves = np.stack([np.stack([corners[k], corners[(k + 1) % 3]], axis=1) for k in range(3)], axis=1)
        key = np.sort(halves.reshape(-1, 2), axis=1)
        edges, slot_edge = np.unique(key, axis=0, return_inverse=True)
        mid = len(V) + slot_edge.reshape(-1, 3)  # the new vertex of each face's edges k -> k+1
        V = np.vstack([V, 0.5 * (V[edges[:, 0]] + V[edges[:, 1]])])
        a, b, c = corners
        ab, bc, ca = mid[:, 0], mid[:, 1], mid[:, 2]
        F = np.vstack([np.stack(t, axis=1) for t in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])
    return V, F


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.write("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in V))
        f.write("".join("f %d %d %d\n" % tuple(t + 1) for t in F))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh", type=pathlib.Path)
    parser.add_argument("out_dir", type=pathlib.Path)
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args(argv)
    if any(level < 1 or level > 6 for level in args.levels):
        parser.error("levels must be between 1 and 6 (each level has four times the faces)")
    V, F = read_obj(args.mesh)
    if len(F) == 0:
        parser.error(f"{args.mesh} has no faces")
    args.out_dir.mkdir(parents=True, exist_ok=True)
    for level in sorted(set(args.levels)):
        Vs, Fs = midpoint_subdivide(V, F, level)
        out = args.out_dir / f"{args.mesh.stem}_sub{level}.obj"
        write_obj(out, Vs, Fs)
        print(f"{out}: {len(Vs)} vertices, {len(Fs)} faces")
    return 0


if __name__ == "__main__":
    sys.exit(main())
