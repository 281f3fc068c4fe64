#!/usr/bin/env python3
"""Both methods run until they converge: steps, time per step and time to converge, and the share of
faces within 10 degrees of an axis (what the cubic method is compared with its reference on).

Converged: reldV = max|U_k - U_{k-1}| / max|U_k - V| over all coordinates < --tol (the reference
implementation's stopping rule), or --cap steps, with the plain iteration (acceleration=False). Only
solver.step() is timed; reading the vertices for reldV is not. Runs through gauss_core as the add-on
does.

usage: measure_cubic.py MESH [MESH...] [--runs gauss:4 cubic:0.2 cubic:0.4] [--tol 1e-3] [--cap 1000]
                        [--threads N]
Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python).
"""
import argparse
import os
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
sys.path.insert(0, str(REPO / "tests" / "common"))
sys.path.insert(0, str(REPO / "tests" / "python"))
import gauss_core  # noqa: E402
from measures import aligned_share  # noqa: E402
from meshes import read_obj  # noqa: E402

AXES = np.vstack([np.eye(3), -np.eye(3)])


def run(V, F, method, lam, tol, cap):
    """(steps, per-step ms median, total ms, per-step CPU ms median, set-up ms, share after) of one run
    to convergence. CPU time (all threads) tells what a step costs when other processes hold the cores."""
    t0 = time.perf_counter()
    keyword = {"cubic_lambda": lam} if method == "cubic" else {"lam": lam}
    # The plain iteration, whose reldV is the one computed here from consecutive iterates (accelerated
    # runs: gauss_bench --until, scripts/plot_convergence.py).
    solver = gauss_core.Solver(V, F, method=method, acceleration=False, **keyword)
    setup_ms = (time.perf_counter() - t0) * 1000
    used = np.unique(F)  # unreferenced vertices never move
    previous = solver.vertices[used]
    current = np.empty_like(solver.vertices)
    times, cpu = [], []
    steps = 0
    while steps < cap:
        t, c = time.perf_counter(), time.process_time()
        solver.step()
        times.append((time.perf_counter() - t) * 1000)
        cpu.append((time.process_time() - c) * 1000)
        steps += 1
        solver.vertices_into(current)
        now = current[used]
        moved = np.abs(now - V[used]).max()
        rel = np.abs(now - previous).max() / moved if moved > 0 else 0.0
        previous = now
        if rel < tol:
            break
    return (steps, float(np.median(times)), float(np.sum(times)), float(np.median(cpu)), setup_ms,
            aligned_share(current, F, AXES))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="+")
    parser.add_argument("--runs", nargs="+", default=["gauss:%g" % gauss_core.DEFAULTS["lam"], "cubic:0.2", "cubic:0.4"])
    parser.add_argument("--tol", type=float, default=1e-3)
    parser.add_argument("--cap", type=int, default=1000)
    parser.add_argument("--threads", type=int, default=0)
    args = parser.parse_args()
    if args.threads:
        gauss_core.set_num_threads(args.threads)
    print("mesh method lambda steps step_ms_median ms_to_converge step_cpu_ms_median setup_ms share_before share_after")
    for path in args.meshes:
        V, F = read_obj(path)
        before = aligned_share(V, F, AXES)
        for spec in args.runs:
            method, lam = spec.split(":")
            steps, step_ms, total_ms, cpu_ms, setup_ms, after = run(V, F, method, float(lam), args.tol, args.cap)
            print("%s %s %s %d %.3f %.1f %.3f %.1f %.4f %.4f" % (pathlib.Path(path).name, method, lam, steps, step_ms,
                                                                total_ms, cpu_ms, setup_ms, before, after), flush=True)


if __name__ == "__main__":
    main()
