#!/usr/bin/env python3
"""Per-iteration time of our cubic method against the reference Cubic Stylization.

Runs gauss_bench (--method cubic --style cube) and the reference driver (cubic_reference_driver.cpp,
built by hand as docs/performance.md, "Per iteration against the cubic reference", describes)
alternately, ours then the reference, for --rounds rounds per mesh, both for the same number of
iterations on the same thread count, so that a busy machine's load falls on both alike. Each run
reports the median of its per-iteration times; the line per mesh gives the median over the rounds:

    MESH: ours X ms, reference Y ms, Z.Zx

Usage (from the repository root):
    python3 cpp/bench/compare_cubic_reference.py --reference /path/to/cubic_reference_driver \
        [--bench build/gauss_bench] [--threads 1] [--rounds 3] [--steps 30] [--lambda 0.2] [MESH ...]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_MESHES = [
    "../shared/meshes/small/spot_triangulated_2930.obj",
    "../shared/meshes/bunny/bunny_cubicstylization_6172.obj",
    "../shared/meshes/armadillo/armadillo_libigl_43243.obj",
]


def run(cmd, env=None):
    result = subprocess.run(cmd, cwd=REPO, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(cmd)}\n{result.stdout}{result.stderr}")
    return result.stdout


def ours_ms(bench, mesh, threads, steps, lam):
    out = run([bench, mesh, "--method", "cubic", "--style", "cube", "--lambda", str(lam),
               "--steps", str(steps), "--threads", str(threads), "--acceleration", "on"])
    match = re.search(r"^step_ms_median: ([0-9.]+)$", out, re.M)
    if not match:
        sys.exit(f"no step_ms_median in the output of {bench}:\n{out}")
    return float(match.group(1))


def reference_ms(reference, mesh, threads, steps, lam):
    env = dict(os.environ, IGL_NUM_THREADS=str(threads))  # libigl's parallel_for reads it
    out = run([reference, mesh, str(lam), str(steps), str(10 * steps)], env=env)
    match = re.search(r"stopped after (\d+) .* ms_per_iter_median ([0-9.]+)", out)
    if not match:
        sys.exit(f"no ms_per_iter_median in the output of {reference}:\n{out}")
    if int(match.group(1)) < steps:
        sys.exit(f"the reference converged after {match.group(1)} of {steps} iterations on {mesh}; use fewer --steps")
    return float(match.group(2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reference", required=True, help="the built cubic_reference_driver")
    parser.add_argument("--bench", default="build/gauss_bench", help="our gauss_bench (relative to the repository)")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--steps", type=int, default=30)
    parser.add_argument("--lambda", dest="lam", type=float, default=0.2)
    parser.add_argument("--verbose", action="store_true", help="also print every round's two medians")
    parser.add_argument("meshes", nargs="*", default=DEFAULT_MESHES, help="paths relative to the repository")
    args = parser.parse_args()
    if args.threads < 1 or args.rounds < 1 or args.steps < 1:
        parser.error("--threads, --rounds and --steps must be positive")
    reference = os.path.abspath(args.reference)
    bench = os.path.join(REPO, args.bench) if not os.path.isabs(args.bench) else args.bench
    for path in (reference, bench):
        if not os.access(path, os.X_OK):
            parser.error(f"not an executable: {path}")
    print(f"threads {args.threads}, {args.rounds} rounds of {args.steps} iterations, lambda {args.lam}")
    for mesh in args.meshes:
        ours, ref = [], []
        for _ in range(args.rounds):
            ours.append(ours_ms(bench, mesh, args.threads, args.steps, args.lam))
            ref.append(reference_ms(reference, mesh, args.threads, args.steps, args.lam))
            if args.verbose:
                print(f"  round {len(ours)}: ours {ours[-1]:.2f} ms, reference {ref[-1]:.2f} ms", flush=True)
        o, r = statistics.median(ours), statistics.median(ref)
        print(f"{os.path.basename(mesh)}: ours {o:.2f} ms, reference {r:.2f} ms, {r / o:.1f}x", flush=True)


if __name__ == "__main__":
    main()
