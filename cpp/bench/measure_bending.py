#!/usr/bin/env python3
"""ARAP's bending stiffness against the edge length
(docs/resolution.md#bending-araps-stiffness-shrinks-with-the-edge-length): a flat triangle lattice of spacing
h bent into a cylinder of curvature kappa (an isometry), ARAP's energy with its optimal rotations
(Solver.arap_energy after set_vertices) per unit area, over a kappa^2 (a: the face area): c_A; and the bending
term sum_ij w_ij |R_i - R_j|_F^2 of the cylinder's own rotations per unit area over kappa^2: c_B.

usage: measure_bending.py [--spacings 20 40 80] [--radii 1 0.5]
Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python).
"""
import argparse
import os
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
import gauss_core  # noqa: E402


def lattice(n):
    """A triangle lattice of n edges across the unit square (rows shifted by half an edge)."""
    h = 1.0 / n
    rows = int(round(1.0 / (h * np.sqrt(3) / 2)))
    index, V, F = {}, [], []
    for j in range(rows + 1):
        for i in range(n + 1):
            index[i, j] = len(V)
            V.append(((i + 0.5 * (j % 2)) * h, j * h * np.sqrt(3) / 2, 0.0))
    for j in range(rows):
        for i in range(n):
            if j % 2 == 0:
                F += [(index[i, j], index[i + 1, j], index[i, j + 1]),
                      (index[i + 1, j], index[i + 1, j + 1], index[i, j + 1])]
            else:
                F += [(index[i, j], index[i + 1, j], index[i + 1, j + 1]),
                      (index[i, j], index[i + 1, j + 1], index[i, j + 1])]
    V = np.array(V)
    return V / (V.max(0) - V.min(0)).max(), np.array(F, np.int64)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--spacings", type=int, nargs="+", default=[20, 40, 80])
    p.add_argument("--radii", type=float, nargs="+", default=[1.0, 0.5])
    a = p.parse_args()
    print("| edges across | mean face area | radius | c_A | c_B |")
    print("|---|---|---|---|---|")
    for n in a.spacings:
        V, F = lattice(n)
        area = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
        for r in a.radii:
            angle = (V[:, 0] - 0.5) / r  # the rotation about y that carries the plane onto the cylinder
            bent = np.stack([r * np.sin(angle), V[:, 1], r * (1 - np.cos(angle))], axis=1)
            solver = gauss_core.Solver(V, F, acceleration=False)
            solver.set_vertices(bent)
            bend = 0.0
            for k in range(3):  # slot k: the edge (k, k+1), weight cot(opposite angle) / 2
                i, j, o = F[:, k], F[:, (k + 1) % 3], F[:, (k + 2) % 3]
                u, w = V[i] - V[o], V[j] - V[o]
                cot = (u * w).sum(1) / np.linalg.norm(np.cross(u, w), axis=1)
                bend += (0.5 * cot * 4 * (1 - np.cos(angle[i] - angle[j]))).sum()  # |R_i - R_j|_F^2
            kappa2, total = 1 / r ** 2, area.sum()
            print(f"| {n} | {area.mean():.3g} | {r:g} | {solver.arap_energy / (total * kappa2 * area.mean()):.3f} | "
                  f"{bend / (total * kappa2):.3f} |")


if __name__ == "__main__":
    main()
