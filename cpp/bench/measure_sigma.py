#!/usr/bin/env python3
"""Does a run converge at a high sigma? Steps to reldV < --tol (or the cap), the share of faces within
10 degrees of the style's normals, and the faces that flip: over the last --window steps, the share of
faces whose nearest preferred normal changed to another and back (A -> B -> A) between steps; then
the faces whose normal step (Eqs. 21-22) is not a descent step at the end, so that it falls back to a
small gradient step, and those that switched between the two over the last step (the tables of
docs/high_sigma.md).

usage: measure_sigma.py MESH [MESH...] [--sigmas 4 8 12 20] [--style cube] [--lam 4] [--tol 1e-3]
                        [--cap 1500] [--window 20] [--resolution-independent] [--ramp STEPS] [--plain]
                        [--paper-step]
Runs the accelerated iteration as the add-on does (--plain: without it). --ramp: continuation in
sigma. --paper-step: the paper's normal step at every sigma (paper_step_any_sigma), as before
2026-12-07; without it the solver takes its trust-region step above gauss_core.PAPER_STEP_MAX_SIGMA,
and the uphill and switching columns still count the paper's step, which that run no longer takes.
Imports gauss_core from $GAUSS_BUILD_DIR/python
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


def edge_weights(V, F):
    """(#F, 3): the summed cotangent weight (cot / 2 of each opposite angle) of the edge in each slot,
    slot k the edge F[:, k] -> F[:, k + 1], as the solver's normal step weighs it (ill-shaped triangles'
    floor left out)."""
    w = np.empty(F.shape)
    for k in range(3):
        a, b, c = V[F[:, k]], V[F[:, (k + 1) % 3]], V[F[:, (k + 2) % 3]]
        u, v = a - c, b - c
        w[:, k] = 0.5 * np.einsum("ij,ij->i", u, v) / np.linalg.norm(np.cross(u, v), axis=1)
    key = np.sort(np.stack([F, np.roll(F, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    _, inverse = np.unique(key, axis=0, return_inverse=True)
    summed = np.bincount(inverse.ravel(), weights=w.ravel())
    return summed[inverse.ravel()].reshape(F.shape)


def uphill_newton(rest, U, F, style, lam):
    """(#F,) bool: faces whose first-round normal step (Eqs. 21-22; u = 0, e* = e) is not a descent
    direction at the vertices U, so newton_normal falls back to its small gradient step. Without
    Resolution Independent's per-face scaling of lambda: with --resolution-independent, an estimate."""
    scale = (rest.max(axis=0) - rest.min(axis=0)).max()  # the solver's normalized frame
    W = lam * edge_weights(rest / scale, F)
    X = np.asarray(U) / scale
    n, _ = face_normals(X, F)
    grad = np.asarray(style.gradient(n))
    H = -np.asarray(style.hessian(n))
    for k in range(3):
        e = X[F[:, (k + 1) % 3]] - X[F[:, k]]
        H += W[:, k, None, None] * e[:, :, None] * e[:, None, :]
    with np.errstate(all="ignore"):
        x = np.linalg.solve(H, grad[:, :, None])[:, :, 0]
        d = x - np.einsum("ij,ij->i", x, n)[:, None] * n
        ok = np.isfinite(d).all(axis=1) & (np.einsum("ij,ij->i", d, d) > 1e-16 * np.einsum("ij,ij->i", x, x))
        return ~(ok & (np.einsum("ij,ij->i", d, grad) >= 0))


def run(V, F, style, sigma, lam, tol, cap, window, independent=False, ramp=0, plain=False, paper_step=False):
    """(steps, converged, share, flipping share over the last `window` steps, last reldV, uphill share,
    switching share): uphill, the faces whose normal step falls back to the gradient at the last step
    (uphill_newton); switching, those that changed between Newton and the fallback over the last step.
    ramp > 0: continuation, sigma rising linearly from the default to `sigma` over `ramp` steps, and
    the run does not stop before it ends."""
    solver = gauss_core.Solver(V, F, lam=lam, resolution_independent=independent, paper_step_any_sigma=paper_step)
    if plain:
        solver.acceleration = False
    s = gauss_core.Style.preset(style, sigma=sigma)
    solver.set_styles([s])
    normals = np.asarray(s.normals)
    history = []
    steps = 0
    start = gauss_core.DEFAULTS["sigma"]
    before = solver.vertices
    while steps < cap:
        if steps < ramp and sigma > start:
            solver.set_styles([gauss_core.Style.preset(style, sigma=start + (sigma - start) * (steps + 1) / ramp)])
        before = solver.vertices
        solver.step()
        steps += 1
        history.append(nearest(solver.vertices, F, normals))
        history = history[-window:]
        if solver.last_reldv < tol and steps >= ramp:  # converged at the set sigma, not on the way
            break
    H = np.array(history)
    flips = np.zeros(len(F), bool)
    for t in range(2, len(H)):
        flips |= (H[t] != H[t - 1]) & (H[t] == H[t - 2])
    U = solver.vertices
    # The step's normals are taken at the vertices it started from (momentum's point aside).
    up, up_before = (uphill_newton(V, X, F, s, lam) for X in (U, before))
    return (steps, solver.last_reldv < tol, aligned_share(U, F, normals), float(flips.mean()), solver.last_reldv,
            float(up.mean()), float((up != up_before).mean()))


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
    p.add_argument("--plain", action="store_true", help="without the acceleration (momentum)")
    p.add_argument("--paper-step", action="store_true", help="the paper's normal step at every sigma")
    a = p.parse_args()
    print("| mesh | sigma | steps | share | flipping faces | last reldV | uphill Newton | switching |")
    print("|---|---|---|---|---|---|---|---|")
    for path in a.meshes:
        V, F = read_obj(path)
        for sigma in a.sigmas:
            steps, ok, share, flips, reldv, up, switching = run(V, F, a.style, sigma, a.lam, a.tol, a.cap, a.window,
                                                 a.resolution_independent, a.ramp, a.plain, a.paper_step)
            print(f"| {pathlib.Path(path).stem} | {sigma:g} | {steps if ok else f'not within {steps}'} | "
                  f"{share:.4f} | {flips:.3f} | {reldv:.2g} | {up:.3f} | {switching:.3f} |", flush=True)


if __name__ == "__main__":
    main()
