#!/usr/bin/env python3
"""How close does a stylized mesh's normal distribution come to an example's? The table of
docs/styles.md#gauss-map: for each example (a cube, an icosahedron, a decimated bunny) and each target
mesh, the earth mover's distance (radians; ground metric: the angle on the sphere) between the
area-weighted Gauss-map histograms (a Fibonacci lattice of --cells cells) of the example and of the
target stylized by From Object's style (the example's --directions dominant directions, a Custom style)
and by the Gauss Map style (the example's whole normal distribution, Style.gauss_map); with the cube,
also the share of faces within 10 degrees of the axes, against the Cube preset's.

usage: measure_gauss_map.py [TARGET.obj ...] [--sigma 4] [--lam 4] [--steps 300] [--cells 400]
                            [--directions 32] [--decimate-cells 9] [--every-mesh]
--every-mesh: instead, every mesh of ../shared/meshes stylized towards the decimated bunny's Gauss map
(until converged, at most 300 steps): whether the result is finite, how far it grew (its largest
distance from the input's centre over the input's) and the steps it took, or the solver's refusal.
Targets default to Spot and the 3K bunny of ../shared/meshes. The decimated bunny is the 3K bunny
collapsed on a grid of --decimate-cells cells along its longest side (vertex clustering).
Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python). Takes about a minute.
"""
import argparse
import importlib.util
import os
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[1]
MESHES = REPO.parent / "shared" / "meshes"
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
sys.path.insert(0, str(REPO / "tests" / "common"))
import gauss_core  # noqa: E402
from measures import (  # noqa: E402
    aligned_share, face_normals, fibonacci_lattice, gauss_histogram, mesh_gauss_histogram, sphere_emd,
)
from example_meshes import decimated, icosahedron  # noqa: E402
from mesh_files import read_mesh  # noqa: E402


def _addon_directions():
    """The add-on's sphere/directions.py (numpy only), loaded without the add-on's package (bpy)."""
    path = REPO / "python_addon" / "gauss_stylization" / "sphere" / "directions.py"
    spec = importlib.util.spec_from_file_location("gauss_directions", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


directions = _addon_directions()


def stylize(V, F, style, args):
    solver = gauss_core.Solver(V, F, lam=args.lam)
    solver.set_styles([style])
    solver.step_until(None, args.steps)
    return np.asarray(solver.vertices)


def every_mesh(args):
    bunny_V, bunny_F = read_mesh(MESHES / "bunny" / "bunny_odedstein_3301.obj")
    normals, areas = face_normals(*decimated(bunny_V, bunny_F, args.decimate_cells))
    cells, shares = directions.gauss_map(normals, areas)
    style = gauss_core.Style.gauss_map(cells, shares, sigma=args.sigma)
    print("| mesh | faces | finite | grew | steps (converged?) |")
    print("|---|---|---|---|---|")
    for path in sorted(MESHES.rglob("*")):
        if path.suffix not in (".obj", ".ply"):
            continue
        V, F = read_mesh(path)
        name = path.relative_to(MESHES)
        try:
            solver = gauss_core.Solver(V, F, lam=args.lam)
        except (ValueError, MemoryError) as exc:
            print("| %s | %d | refused: %s | | |" % (name, len(F), exc), flush=True)
            continue
        solver.set_styles([style])
        steps = solver.step_until(None, 300)
        out = np.asarray(solver.vertices)
        used = np.unique(F)
        centre = V[used].mean(axis=0)
        grew = np.linalg.norm(out[used] - centre, axis=1).max() / np.linalg.norm(V[used] - centre, axis=1).max()
        print("| %s | %d | %s | %.3f | %d (%s) |" % (name, len(F), bool(np.isfinite(out).all()), grew, steps,
                                                 "yes" if steps < 300 else "no"), flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("targets", nargs="*", default=[str(MESHES / "small" / "spot_triangulated_2930.obj"),
                                                       str(MESHES / "bunny" / "bunny_odedstein_3301.obj")])
    parser.add_argument("--sigma", type=float, default=4.0)
    parser.add_argument("--lam", type=float, default=4.0)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--cells", type=int, default=400)
    parser.add_argument("--directions", type=int, default=32)
    parser.add_argument("--decimate-cells", type=int, default=9)
    parser.add_argument("--every-mesh", action="store_true")
    args = parser.parse_args()
    if args.every_mesh:
        every_mesh(args)
        return

    lattice = fibonacci_lattice(args.cells)
    bunny_V, bunny_F = read_mesh(MESHES / "bunny" / "bunny_odedstein_3301.obj")
    examples = {
        "cube": read_mesh(MESHES / "small" / "cube_libigl_8.obj"),
        "icosahedron": icosahedron(),
        "decimated bunny (%d faces)" % len(decimated(bunny_V, bunny_F, args.decimate_cells)[1]):
            decimated(bunny_V, bunny_F, args.decimate_cells),
    }
    cube = gauss_core.Style.preset("cube", sigma=args.sigma)
    print("sigma %g, lambda %g, up to %d steps; EMD in radians on a %d-cell Fibonacci lattice"
          % (args.sigma, args.lam, args.steps, args.cells))
    print("| target | example | input EMD | From Object (%d) EMD | Gauss Map EMD | cube share: Cube / From Object / "
          "Gauss Map |" % args.directions)
    print("|---|---|---|---|---|---|")
    for target in args.targets:
        V, F = read_mesh(target)
        cube_share = None
        for name, (EV, EF) in examples.items():
            normals, areas = face_normals(EV, EF)
            example_hist = gauss_histogram(normals, areas, lattice)
            found, _ = directions.dominant_directions(gauss_core, normals, areas, args.directions)
            from_object = gauss_core.Style(normals=found, sigma=args.sigma)
            cells, shares = directions.gauss_map(normals, areas)
            gauss_map = gauss_core.Style.gauss_map(cells, shares, sigma=args.sigma)
            emd = {}
            results = {}
            for label, style in (("from_object", from_object), ("gauss_map", gauss_map)):
                results[label] = stylize(V, F, style, args)
                emd[label] = sphere_emd(mesh_gauss_histogram(results[label], F, lattice), example_hist, lattice)
            emd_in = sphere_emd(mesh_gauss_histogram(V, F, lattice), example_hist, lattice)
            share = ""
            if name == "cube":
                if cube_share is None:
                    cube_share = aligned_share(stylize(V, F, cube, args), F, cube.normals)
                share = "%.3f / %.3f / %.3f" % (cube_share, aligned_share(results["from_object"], F, cube.normals),
                                                aligned_share(results["gauss_map"], F, cube.normals))
            print("| %s | %s | %.4f | %.4f | %.4f | %s |" % (pathlib.Path(target).stem, name, emd_in,
                                                         emd["from_object"], emd["gauss_map"], share), flush=True)


if __name__ == "__main__":
    main()
