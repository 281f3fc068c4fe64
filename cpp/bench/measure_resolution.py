#!/usr/bin/env python3
"""Does Lambda mean the same at any tessellation? Each mesh, midpoint-subdivided (scripts/subdivide_mesh.py),
stylized until converged with resolution_independent off and on: the converged share at each level
against the coarsest's, and at the original vertices the mean (max) distance to the coarsest result
in % of the bounding-box diagonal (docs/resolution.md, docs/performance.md#resolution-independence).

usage: measure_resolution.py MESH [MESH...] [--levels 0 1 2] [--runs gauss:cube:2 cubic:cube:0.2 ...]
                             [--modes off on] [--tol 1e-3] [--cap 3000] [--reference-face-area A]
A run is METHOD:STYLE:LAMBDA (the method's own lambda; the cubic method's style is always the cube).
Prints one line per run, then the table.
--reference-face-area runs the setting's "on" mode with that reference density instead of
settings::reference_face_area, through $GAUSS_BUILD_DIR/gauss_bench --reference-face-area (Python keeps
the setting's own).
Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python).
"""
import argparse
import os
import pathlib
import re
import subprocess
import sys
import tempfile

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build"))
sys.path.insert(0, str(BUILD / "python"))
sys.path.insert(0, str(REPO / "tests" / "common"))
sys.path.insert(0, str(REPO / "scripts"))
import gauss_core  # noqa: E402
from measures import aligned_share  # noqa: E402
from subdivide_mesh import midpoint_subdivide, read_obj, write_obj  # noqa: E402


def stylize(V, F, method, style, lam, independent, tol, cap, sigma=None):
    """(result vertices, steps, converged, share within 10 degrees of the style's normals)."""
    keyword = {"cubic_lambda": lam} if method == "cubic" else {"lam": lam}
    solver = gauss_core.Solver(V, F, method=method, resolution_independent=independent, **keyword)
    s = gauss_core.Style.preset("cube" if method == "cubic" else style,
                                **({} if sigma is None else {"sigma": sigma}))
    solver.set_styles([s])
    steps = solver.step_until(tol, cap)
    U = solver.vertices
    return U, steps, bool(solver.last_reldv < tol), aligned_share(U, F, s.normals)


def stylize_in_bench(V, F, method, style, lam, tol, cap, reference_face_area):
    """stylize() with resolution_independent on at another reference density, by gauss_bench."""
    with tempfile.TemporaryDirectory() as tmp:
        mesh, out = pathlib.Path(tmp) / "in.obj", pathlib.Path(tmp) / "out.obj"
        write_obj(mesh, V, F)
        report = subprocess.run(
            [str(BUILD / "gauss_bench"), str(mesh), "--method", method, "--style",
             "cube" if method == "cubic" else style, "--lambda", repr(lam), "--until", repr(tol), "--steps",
             str(cap), "--resolution-independent", "--reference-face-area", repr(reference_face_area), "--out",
             str(out)], check=True, capture_output=True, text=True).stdout
        U, _ = read_obj(out)
    steps = re.search(r"^steps_to_converge: (?:not within )?(\d+)", report, re.M)
    share = re.search(r"^axis_share_10deg: \S+ -> (\S+)", report, re.M)
    s = gauss_core.Style.preset("cube" if method == "cubic" else style)
    return (U, int(steps.group(1)), "not within" not in report,
            float(share.group(1)) if share else aligned_share(U, F, s.normals))


def compare(levels_results, n0, diagonal):
    """Per level: (share, mean %, max % distance at the first n0 vertices to level 0's result)."""
    base = levels_results[0][0][:n0]
    out = []
    for U, steps, ok, share in levels_results:
        d = np.linalg.norm(U[:n0] - base, axis=1) / diagonal * 100
        out.append((share, float(d.mean()), float(d.max()), steps, ok))
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("meshes", nargs="+")
    p.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
    p.add_argument("--runs", nargs="+", default=[f"gauss:{s}:{l}" for s in ("cube", "tetrahedron") for l in (2, 4, 8)]
                   + [f"cubic:cube:{l}" for l in (0.2, 0.4, 0.8)])
    p.add_argument("--modes", nargs="+", default=["off", "on"])
    p.add_argument("--tol", type=float, default=1e-3)
    p.add_argument("--cap", type=int, default=3000)
    p.add_argument("--reference-face-area", type=float, default=None)
    a = p.parse_args()
    rows = []
    for path in a.meshes:
        V0, F0 = read_obj(path)
        diagonal = float(np.linalg.norm(V0.max(0) - V0.min(0)))
        meshes = [midpoint_subdivide(V0, F0, level) for level in a.levels]
        for run in a.runs:
            method, style, lam = run.split(":")
            for mode in a.modes:
                results = []
                for (V, F), level in zip(meshes, a.levels):
                    if mode == "on" and a.reference_face_area is not None:
                        results.append(stylize_in_bench(V, F, method, style, float(lam), a.tol, a.cap,
                                                        a.reference_face_area))
                    else:
                        results.append(stylize(V, F, method, style, float(lam), mode == "on", a.tol, a.cap))
                    print(f"# {pathlib.Path(path).stem} level {level} {run} {mode}: steps {results[-1][1]}"
                          f" converged {results[-1][2]} share {results[-1][3]:.3f}", flush=True)
                for level, r in zip(a.levels, compare(results, len(V0), diagonal)):
                    rows.append((pathlib.Path(path).stem, run, mode, level) + r)
    print("| mesh | run | independent | level | share | mean % | max % | steps |")
    print("|---|---|---|---|---|---|---|---|")
    for m, run, mode, level, share, mean, mx, steps, ok in rows:
        print(f"| {m} | {run} | {mode} | {level} | {share:.3f} | {mean:.2f} | {mx:.2f} | "
              f"{steps if ok else f'not within {steps}'} |")


if __name__ == "__main__":
    main()
