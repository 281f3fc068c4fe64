#!/usr/bin/env python3
"""Does a run converge at a high sigma? Steps to reldV < --tol (or the cap), the share of faces within
10 degrees of the style's normals, and the faces that flip: over the last --window steps, the share of
faces whose nearest preferred normal changed to another and back (A -> B -> A) between steps
(the table under *High sigma never converges* in docs/limitations.md).

usage: measure_sigma.py MESH [MESH...] [--sigmas 4 8 12 20] [--style cube] [--lam 4] [--tol 1e-3]
                        [--cap 1500] [--window 20] [--resolution-independent] [--ramp STEPS]
Runs the accelerated iteration as the add-on does. Imports gauss_core from $GAUSS_BUILD_DIR/python
(default: <repo>/build/python).
"""
import argparse
import os
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
sys.path.insert(0, str(REPO / "tests" / "common"))
sys.path.insert(0, str(REPO / "scripts"))
import gauss_core  # noqa: E402
from measures import aligned_share, face_normals  # noqa: E402
from subdivide_mesh import read_obj  # noqa: E402


def nearest(V, F, normals):
    n, _ = face_normals(V, F)
    return np.argmax(n @ normals.T, axis=1)


def run(V, F, style, sigma, lam, tol, cap, window, independent=False, ramp=0):
    """(steps, converged, share, flipping share over the last `window` steps, last reldV).
    ramp > 0: continuation, sigma rising linearly from the default to `sigma` over `ramp` steps."""
    solver = gauss_core.Solver(V, F, lam=lam, resolution_independent=independent)
    s = gauss_core.Style.preset(style, sigma=sigma)
    solver.set_styles([s])
    normals = np.asarray(s.normals)
    history = []
    steps = 0
    start = gauss_core.DEFAULTS["sigma"]
    while steps < cap:
        if steps < ramp and sigma > start:
            solver.set_styles([gauss_core.Style.preset(style, sigma=start + (sigma - start) * (steps + 1) / ramp)])
        solver.step()
        steps += 1
        history.append(nearest(solver.vertices, F, normals))
        history = history[-window:]
        if solver.last_reldv < tol:
            break
    H = np.array(history)
    flips = np.zeros(len(F), bool)
    for t in range(2, len(H)):
        flips |= (H[t] != H[t - 1]) & (H[t] == H[t - 2])
    U = solver.vertices
    return steps, solver.last_reldv < tol, aligned_share(U, F, normals), float(flips.mean()), solver.last_reldv


def main():
    p = argparse.ArgumentParser()
    p.add_argument("meshes", nargs="+")
    p.add_argument("--sigmas", type=float, nargs="+", default=[4, 8, 12, 20])
    p.add_argument("--style", default="cube")
    p.add_argument("--lam", type=float, default=4.0)
    p.add_argument("--tol", type=float, default=1e-3)
    p.add_argument("--cap", type=int, default=1500)
    p.add_argument("--window", type=int, default=20)
    p.add_argument("--resolution-independent", action="store_true")
    p.add_argument("--ramp", type=int, default=0, help="continuation in sigma over this many steps")
    a = p.parse_args()
    print("| mesh | sigma | steps | share | flipping faces | last reldV |")
    print("|---|---|---|---|---|---|")
    for path in a.meshes:
        V, F = read_obj(path)
        for sigma in a.sigmas:
            steps, ok, share, flips, reldv = run(V, F, a.style, sigma, a.lam, a.tol, a.cap, a.window,
                                                 a.resolution_independent, a.ramp)
            print(f"| {pathlib.Path(path).stem} | {sigma:g} | {steps if ok else f'not within {steps}'} | "
                  f"{share:.4f} | {flips:.3f} | {reldv:.2g} |", flush=True)


if __name__ == "__main__":
    main()
