#!/usr/bin/env python3
"""Scale measurement: set-up time, time per step and memory of the solver on a ~1M-face mesh.

The mesh is scale_mesh.cube_sphere, a lumpy sphere made from a subdivided cube, n by n quads per side
(n = 289: 501,128 vertices, 1,002,252 faces). Runs through gauss_core as the add-on does;
scripts/measure_scale.sh wraps it in /usr/bin/time -v for the peak resident set size.

usage: measure_scale.py [--n 289] [--steps 5] [--style NAME] [--threads N]   (style: gauss_core.DEFAULTS)
Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python).
"""
import argparse
import os
import pathlib
import resource
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
import gauss_core  # noqa: E402
from scale_mesh import cube_sphere  # noqa: E402  (the generated mesh, shared with Blender's measurements)


def peak_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: kilobytes


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=289)
    ap.add_argument("--steps", type=int, default=5)
    ap.add_argument("--style", default=gauss_core.DEFAULTS["preset"], choices=gauss_core.PRESETS)
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()
    if args.threads > 0:
        gauss_core.set_num_threads(args.threads)

    t = time.perf_counter()
    V, F = cube_sphere(args.n)
    print(f"mesh: {len(V):,} vertices, {len(F):,} faces (generated in {time.perf_counter() - t:.2f} s); "
          f"threads: {gauss_core.get_num_threads()}")
    rss_mesh = peak_rss_mb()

    t = time.perf_counter()
    progress = gauss_core.Progress()
    s = gauss_core.Solver(V, F, progress=progress)
    s.set_styles([gauss_core.Style.preset(args.style)])
    setup = time.perf_counter() - t
    rss_setup = peak_rss_mb()

    step_times = []
    for _ in range(args.steps):
        t = time.perf_counter()
        s.step()
        step_times.append(time.perf_counter() - t)
    phases = {k: v for k, v in s.last_step_ms.items() if k != "threads"}  # milliseconds per phase
    out = np.empty((len(V), 3), np.float32)
    t = time.perf_counter()
    s.vertices_into(out)
    readout = time.perf_counter() - t
    moved = np.abs(out - V).max()

    print(f"setup_s: {setup:.2f}")
    print("setup phases (s): " + ", ".join(f"{k} {v:.2f}" for k, v in progress.seconds.items()))
    print(f"step_s: median {np.median(step_times):.3f}, first {step_times[0]:.3f}, all "
          + " ".join(f"{x:.3f}" for x in step_times))
    print("last step phases (ms): " + ", ".join(f"{k} {v:.0f}" for k, v in phases.items()))
    print(f"vertices_into float32: {readout * 1e3:.1f} ms; finite: {bool(np.isfinite(out).all())}; "
          f"max displacement: {moved:.4f}")
    print(f"peak_rss_mb: after mesh {rss_mesh:.0f}, after setup {rss_setup:.0f}, at end {peak_rss_mb():.0f}")
    if not np.isfinite(out).all():
        sys.exit("non-finite vertices")


if __name__ == "__main__":
    main()
