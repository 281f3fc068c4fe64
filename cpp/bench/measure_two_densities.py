#!/usr/bin/env python3
"""Two objects of very different density, stylized with the same settings: do they look alike?
Each mesh is normalized (bounding-box centre at the origin, longest side 1), stylized until converged
with resolution_independent off and on, and compared: the share of faces within 10 degrees of the
style's normals, and the shape distance, the mean distance from each vertex of the coarse result to
the nearest vertex of the fine one (in % of the diagonal; the inputs' own distance is the floor).

usage: measure_two_densities.py COARSE FINE [--style cube] [--lam 4] [--tol 1e-3] [--cap 3000]
Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python); needs scipy.
"""
import argparse
import pathlib
import sys

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from measure_resolution import read_obj, stylize  # noqa: E402


def normalized(V):
    lo, hi = V.min(0), V.max(0)
    return (V - 0.5 * (lo + hi)) / (hi - lo).max()


def distance(A, B):
    return float(cKDTree(B).query(A)[0].mean() / np.sqrt(3.0) * 100)  # diagonal of a unit box: <= sqrt(3)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("coarse")
    p.add_argument("fine")
    p.add_argument("--style", default="cube")
    p.add_argument("--lam", type=float, default=4.0)
    p.add_argument("--tol", type=float, default=1e-3)
    p.add_argument("--cap", type=int, default=3000)
    a = p.parse_args()
    (Vc, Fc), (Vf, Ff) = [read_obj(m) for m in (a.coarse, a.fine)]
    Vc, Vf = normalized(Vc), normalized(Vf)
    print(f"inputs: distance {distance(Vc, Vf):.2f}%")
    print("| resolution_independent | coarse share | fine share | shape distance |")
    print("|---|---|---|---|")
    for on in (False, True):
        Uc, _, okc, sc = stylize(Vc, Fc, "gauss", a.style, a.lam, on, a.tol, a.cap)
        Uf, _, okf, sf = stylize(Vf, Ff, "gauss", a.style, a.lam, on, a.tol, a.cap)
        print(f"| {'on' if on else 'off'} | {sc:.3f} | {sf:.3f} | {distance(Uc, Uf):.2f}% |"
              + ("" if okc and okf else " (not converged)"), flush=True)


if __name__ == "__main__":
    main()
