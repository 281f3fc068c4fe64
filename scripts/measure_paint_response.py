"""How the share of aligned faces answers a painted Region weight: the table of
docs/interactive.md#the-paint-curve.

    GAUSS_BUILD_DIR=$PWD/build python3 scripts/measure_paint_response.py [--linear] [--k K] [--scales]
        [--resolution-independent [--old-curve]] [--pull P] [--method gauss|cubic] [--steps N] [--until-converged]
        [--lams 2 4 8] [MESH ...]

Runs gauss_core as the add-on does for one Cube style slot whose Region carries the weights, Other
Faces Unstyled (default meshes: Spot and the 6K bunny, ../shared/meshes; lambda 2, 4, 8; 100 steps):

- a uniform weight w = 0, .25, .5, .75, 1: the area-weighted share of faces within 10 degrees of a
  cube normal, against the straight line share(0) + w (share(1) - share(0)), and the largest gap;
- a gradient of vertex weights from 0 to 1 along the mesh's longest axis (a face: the mean of its
  corners'): the share over the faces of the light third (weight below 1/3) and of the heavy third
  (above 2/3), and their difference.

Weights become strengths through the add-on's curve (python_addon/gauss_stylization/settings/
paint_curve.py, loaded by path), for the solver's Resolution Independent as given (default off, the
paper's method; --old-curve: with it on, the curve objects saved under settings version 3 keep; --pull:
another onset p0 than the add-on's, k = ln(lambda / p0)); --linear gives the weights to the solver as they
are (the rule before the curve), --k one steepness for every lambda. --until-converged steps each run
until reldV < 1e-3, at most --steps (default 400 then). --scales instead prints the share for a uniform mu
scale s (the raw response the curve is derived from).
"""
import argparse
import importlib.util
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.environ.get("GAUSS_BUILD_DIR", os.path.join(ROOT, "build")), "python"))
sys.path.insert(0, os.path.join(ROOT, "tests", "common"))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))

import gauss_core  # noqa: E402
from measures import aligned_share  # noqa: E402
from mesh_files import read_mesh  # noqa: E402

MESHES = ("small/spot_triangulated_2930.obj", "bunny/bunny_cubicstylization_6172.obj")
CUBE = np.vstack([np.eye(3), -np.eye(3)])
WEIGHTS = (0.0, 0.25, 0.5, 0.75, 1.0)
SCALES = (0.0, 0.003, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0)


def _curve():
    path = os.path.join(ROOT, "python_addon", "gauss_stylization", "settings", "paint_curve.py")
    spec = importlib.util.spec_from_file_location("paint_curve", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


TOLERANCE = 1e-3  # --until-converged


def _stylized(V, F, lam, face_strength, method, steps, independent, until_converged=False):
    strengths = {"cubic_lambda": lam} if method == "cubic" else {"lam": lam}
    solver = gauss_core.Solver(V, F, method=method, resolution_independent=independent, **strengths)
    solver.set_styles([gauss_core.Style.preset("cube")])
    solver.set_face_weights(np.asarray(face_strength, np.float32).reshape(-1, 1))
    if until_converged:
        solver.step_until(TOLERANCE, steps)
    else:
        solver.step(steps)
    return solver.vertices


def _share(V, F, lam, face_strength, method, steps, independent, until_converged=False):
    return aligned_share(_stylized(V, F, lam, face_strength, method, steps, independent, until_converged),
                         F, CUBE)


def _gradient(V, F):
    """Vertex weights 0 -> 1 along the longest principal axis; faces: the mean of their corners'."""
    centred = V - V.mean(axis=0)
    axis = np.linalg.svd(centred, full_matrices=False)[2][0]
    along = centred @ axis
    vertex = (along - along.min()) / (along.max() - along.min())
    return vertex[F].mean(axis=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("meshes", nargs="*", default=MESHES, help="OBJ or PLY paths, relative to ../shared/meshes")
    parser.add_argument("--linear", action="store_true", help="weights straight to the solver (before the curve)")
    parser.add_argument("--k", type=float, default=None,
                        help="the curve's steepness k for every lambda (default: the add-on's, from the method and lambda)")
    parser.add_argument("--scales", action="store_true", help="share for a uniform mu scale instead")
    parser.add_argument("--resolution-independent", action="store_true", help="the solver's Resolution Independent on")
    parser.add_argument("--old-curve", action="store_true",
                        help="with --resolution-independent: the curve before settings version 4 (old_paint_curve)")
    parser.add_argument("--pull", type=float, default=None,
                        help="the onset p0 of k = ln(lambda / p0) (default: the add-on's, paint_curve.pull_shown)")
    parser.add_argument("--method", default="gauss")
    parser.add_argument("--steps", type=int, default=None, help="steps a run (default 100; --until-converged: 400)")
    parser.add_argument("--until-converged", action="store_true", help="each run until reldV < 1e-3, at most --steps")
    parser.add_argument("--lams", type=float, nargs="+", default=(2.0, 4.0, 8.0),
                        help="Lambda (the cubic method: Cubic Lambda)")
    args = parser.parse_args()
    curve = _curve()
    independent = args.resolution_independent
    if args.old_curve and not independent:
        parser.error("--old-curve is the curve with Resolution Independent: give --resolution-independent too")
    pull = args.pull if args.pull is not None else curve.pull_shown(independent, args.old_curve)
    if args.steps is None:
        args.steps = 400 if args.until_converged else 100
    until = args.until_converged

    def steepness(lam):
        if args.linear:
            return 0.0
        return args.k if args.k is not None else curve.steepness(args.method.upper(), lam, pull)
    shared = os.path.join(ROOT, "..", "shared", "meshes")
    if args.scales:
        print("| mesh | lambda | " + " | ".join("s=%g" % s for s in SCALES) + " |")
    else:
        rule = "linear" if args.linear else "k = %g" % args.k if args.k is not None else "k = ln(lambda / %g)" % pull
        print("rule: %s, method %s, Resolution Independent %s, %s" % (
            rule, args.method, "on" if independent else "off",
            "until reldV < %g, at most %d steps" % (TOLERANCE, args.steps) if until else "%d steps" % args.steps))
        print("| mesh | lambda | " + " | ".join("w=%g" % w for w in WEIGHTS)
              + " | largest gap to the line | gradient: light third | heavy third | heavy - light |")
    print("|---" * (2 + (len(SCALES) if args.scales else len(WEIGHTS) + 4)) + "|")
    for name in args.meshes:
        V, F = read_mesh(os.path.join(shared, name))[:2]
        label = os.path.splitext(os.path.basename(name))[0]
        for lam in args.lams:
            if args.scales:
                shares = [_share(V, F, lam, np.full(len(F), s), args.method, args.steps, independent, until)
                          for s in SCALES]
                print("| %s | %g | %s |" % (label, lam, " | ".join("%.3f" % x for x in shares)), flush=True)
                continue
            k = steepness(lam)
            shares = [_share(V, F, lam, curve.strength(np.full(len(F), w), k), args.method, args.steps, independent,
                             until) for w in WEIGHTS]
            line = [shares[0] + w * (shares[-1] - shares[0]) for w in WEIGHTS]
            gap = max(abs(a - b) for a, b in zip(shares, line))
            face_w = _gradient(V, F)
            result = _stylized(V, F, lam, curve.strength(face_w, k), args.method, args.steps, independent, until)
            light = aligned_share(result, F, CUBE, face_mask=face_w < 1.0 / 3.0)
            heavy = aligned_share(result, F, CUBE, face_mask=face_w > 2.0 / 3.0)
            print("| %s | %g | %s | %.3f | %.3f | %.3f | %.3f |" % (
                label, lam, " | ".join("%.3f" % x for x in shares), gap, light, heavy, heavy - light), flush=True)


if __name__ == "__main__":
    main()
