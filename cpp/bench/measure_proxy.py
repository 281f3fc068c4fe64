#!/usr/bin/env python3
"""Sculpt scale: the proxy of a large mesh (gauss_core.Proxy) measured: its set-up, how well it keeps
the shape, the transfer per tick, memory; with --compare, how far a run on the proxy, carried to the
mesh and finished there by warm-started steps, ends from a run on the mesh from scratch
(docs/performance.md#sculpt-scale).

usage: measure_proxy.py [--n 409 | --mesh PATH [--levels L]] [--target N] [--ticks 100]
                        [--compare] [--lam 4] [--style cube] [--cap 1000] [--tol 1e-3]
                        [--resolution-independent]
--target: the proxy's vertices (default: the add-on's, proxy_run.PROXY_VERTICES);
--n: scale_mesh.cube_sphere(n) (409: 1,003,688 vertices; 580: 2,018,402); --mesh: an OBJ/PLY file,
midpoint-subdivided --levels times (scripts/subdivide_mesh.py). Prints "proxy ..." lines; peak memory
from getrusage (the process's whole peak, solvers included). Imports gauss_core from
$GAUSS_BUILD_DIR/python (default: <repo>/build/python).
"""
import argparse
import os
import pathlib
import resource
import statistics
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
sys.path.insert(0, str(REPO / "tests" / "common"))
sys.path.insert(0, str(REPO / "scripts"))
import gauss_core  # noqa: E402
from measures import style_share  # noqa: E402
from mesh_files import read_mesh  # noqa: E402
from scale_mesh import cube_sphere  # noqa: E402
from subdivide_mesh import midpoint_subdivide  # noqa: E402


def addon_proxy_vertices():
    """The add-on's proxy size (run/proxy_run.py; numpy only, read without importing the add-on's
    package, which needs bpy)."""
    import importlib.util
    path = REPO / "python_addon" / "gauss_stylization" / "run" / "proxy_run.py"
    spec = importlib.util.spec_from_file_location("proxy_run", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.PROXY_VERTICES


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def run(V, F, style, lam, cap, start=None, tol=1e-3, independent=False):
    """(solver, steps, seconds to converge, set-up seconds) of a run until converged from `start`."""
    t = time.perf_counter()
    solver = gauss_core.Solver(V, F, lam=lam, tolerance=tol, resolution_independent=independent)
    solver.set_styles([style])
    setup = time.perf_counter() - t
    if start is not None:
        solver.set_vertices(start)
    t = time.perf_counter()
    steps = solver.step_until(None, cap)
    return solver, steps, time.perf_counter() - t, setup


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=409)
    ap.add_argument("--mesh")
    ap.add_argument("--levels", type=int, default=0)
    ap.add_argument("--target", type=int, default=addon_proxy_vertices())
    ap.add_argument("--ticks", type=int, default=100)
    ap.add_argument("--compare", action="store_true")
    ap.add_argument("--lam", type=float, default=4.0)
    ap.add_argument("--style", default="cube", choices=gauss_core.PRESETS)
    ap.add_argument("--cap", type=int, default=1000)
    ap.add_argument("--tol", type=float, default=1e-3, help="--compare: the tolerance both full-resolution runs step to")
    ap.add_argument("--resolution-independent", action="store_true",
                    help="every solver with Resolution Independent, as the add-on's new objects have it")
    args = ap.parse_args()

    if args.mesh:
        V, F = read_mesh(args.mesh)
        V, F = midpoint_subdivide(V, F, args.levels)
        name = "%s (subdivided %d times)" % (os.path.basename(args.mesh), args.levels)
    else:
        V, F = cube_sphere(args.n)
        name = "cube_sphere(%d)" % args.n
    V, F = np.ascontiguousarray(V, np.float64), np.ascontiguousarray(F, np.int32)
    diagonal = float(np.linalg.norm(np.ptp(V, axis=0)))
    print("proxy mesh: %s, %d vertices, %d faces; threads %d" % (name, len(V), len(F), gauss_core.get_num_threads()),
          flush=True)
    before = peak_mb()

    t, cpu = time.perf_counter(), time.process_time()
    proxy = gauss_core.Proxy(V, F, target_vertices=args.target)
    made, made_cpu = time.perf_counter() - t, time.process_time() - cpu
    face, _bary, offset = proxy.fine_map
    distance = np.linalg.norm(offset[face >= 0], axis=1) / diagonal * 100.0  # face -1: in no face, not mapped
    print("proxy: %d vertices, %d faces, made in %.2f s (CPU %.2f s); mesh to proxy distance %% of the diagonal: "
          "mean %.4f, 95th %.4f, max %.4f" % (len(proxy.vertices), len(proxy.triangles), made, made_cpu, distance.mean(),
                                   np.percentile(distance, 95), distance.max()), flush=True)
    style = gauss_core.Style.preset(args.style)
    t = time.perf_counter()
    small = gauss_core.Solver(proxy.vertices, proxy.triangles, lam=args.lam,
                              resolution_independent=args.resolution_independent)
    small.set_styles([style])
    solver_setup = time.perf_counter() - t
    print("proxy solver set-up: %.2f s; set-up before the first tick: %.2f s" % (solver_setup, made + solver_setup),
          flush=True)

    proxy_now = np.empty((len(proxy.vertices), 3), np.float32)
    out = np.empty((len(V), 3), np.float32)
    step_ms, transfer_ms, transfer_cpu_ms = [], [], []
    for _ in range(args.ticks):  # a live tick's native part: a proxy step, its read-out, the transfer
        t = time.perf_counter()
        small.step()
        small.vertices_into(proxy_now)
        step_ms.append((time.perf_counter() - t) * 1000.0)
        t, cpu = time.perf_counter(), time.process_time()
        proxy.transfer(proxy_now, out)
        transfer_ms.append((time.perf_counter() - t) * 1000.0)
        transfer_cpu_ms.append((time.process_time() - cpu) * 1000.0)
    # CPU time (all threads) depends far less on other processes than wall time does.
    print("proxy tick: step + read-out median %.2f ms, transfer median %.2f ms (CPU of all threads %.2f ms) "
          "(%d ticks); finite %s" % (statistics.median(step_ms), statistics.median(transfer_ms),
                                     statistics.median(transfer_cpu_ms), args.ticks, bool(np.isfinite(out).all())),
          flush=True)
    print("proxy peak memory: %.0f MB (%.0f MB with the mesh alone)" % (peak_mb(), before), flush=True)
    if not args.compare:
        return

    steps_small = small.step_until(None, args.cap)
    small.vertices_into(proxy_now)
    proxy.transfer(proxy_now, out)
    transferred = out.astype(np.float64)
    warm, warm_steps, warm_s, full_setup = run(V, F, style, args.lam, args.cap, start=transferred, tol=args.tol,
                                                independent=args.resolution_independent)
    finished = warm.vertices
    del warm
    scratch, scratch_steps, scratch_s, _ = run(V, F, style, args.lam, args.cap, tol=args.tol,
                                                       independent=args.resolution_independent)
    reference = scratch.vertices
    del scratch
    shares = [style_share(x, F, style) for x in (V, reference, transferred, finished)]
    apart = [np.linalg.norm(x - reference, axis=1).mean() / diagonal * 100.0 for x in (transferred, finished)]
    print("proxy compare: proxy converged after %d more steps (%d ticks before)" % (steps_small, args.ticks))
    print("proxy compare: full-resolution set-up %.2f s; finish from the transfer: %d steps, %.1f s; "
          "from scratch: %d steps, %.1f s" % (full_setup, warm_steps, warm_s, scratch_steps, scratch_s))
    print("proxy compare: share input %.4f, scratch %.4f, transferred %.4f, finished %.4f" % tuple(shares))
    print("proxy compare: mean distance to scratch %% of the diagonal: transferred %.4f, finished %.4f" % tuple(apart))
    print("proxy peak memory: %.0f MB" % peak_mb(), flush=True)


if __name__ == "__main__":
    main()
