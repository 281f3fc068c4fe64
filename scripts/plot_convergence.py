"""Plots how the solver converges, plain and accelerated, for both methods: docs/convergence.png.

    GAUSS_BUILD_DIR=$PWD/build /usr/bin/python3 scripts/plot_convergence.py [MESH] [OUT.png]

Runs gauss_core on the 35K bunny (default ../shared/meshes/bunny/bun_zipper_35947.obj; cube style,
lambda 4, sigma 4, 1 ADMM round) until reldV < 1e-3 (at most 400 steps), once with the plain iteration
and once accelerated (Solver.acceleration), for the Gauss method and the cubic method (its default
lambda), and draws per step: reldV (log scale, with the tolerance), the
area-weighted share of faces within 10 degrees of a cube normal, E_ARAP and the method's own term
(E_g or E_cubic), like Fig. 8 of the paper.

Needs matplotlib, which neither the solver nor its tests use: on Debian `apt-get install
python3-matplotlib` and run it with /usr/bin/python3.
"""
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.environ.get("GAUSS_BUILD_DIR", os.path.join(ROOT, "build")), "python"))
sys.path.insert(0, os.path.join(ROOT, "tests", "common"))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import gauss_core  # noqa: E402
from meshes import read_obj  # noqa: E402
from measures import aligned_share  # noqa: E402

TOLERANCE = 1e-3
CAP = 400


def run(V, F, method, acceleration):
    """Per-step reldV, share, E_ARAP and the method's term until converged; and the wall time."""
    s = gauss_core.Solver(V, F, lam=4.0, admm_iterations=1, method=method, acceleration=acceleration)
    s.set_styles([gauss_core.Style.preset("cube", sigma=4.0)])
    cube = gauss_core.Style.preset("cube").normals
    rows, seconds = [], 0.0
    while len(rows) < CAP and not s.converged:
        t = time.perf_counter()
        s.step()
        seconds += time.perf_counter() - t
        term = s.g_energy if method == "gauss" else s.cubic_energy
        rows.append((s.last_reldv, aligned_share(s.vertices, F, cube), s.arap_energy, term))
    return np.array(rows), seconds


def main():
    mesh = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "..", "shared", "meshes", "bunny",
                                                                "bun_zipper_35947.obj")
    out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "docs", "convergence.png")
    V, F = read_obj(mesh)
    fig, axes = plt.subplots(2, 4, figsize=(13, 5.6), dpi=72)
    for row, (method, term_name) in enumerate((("gauss", "E_g"), ("cubic", "E_cubic"))):
        for acceleration, colour in ((False, "tab:gray"), (True, "tab:blue")):
            data, seconds = run(V, F, method, acceleration)
            steps = np.arange(1, len(data) + 1)
            label = "%s: %d steps, %.1f s" % ("accelerated" if acceleration else "plain", len(data), seconds)
            print(method, label, "share %.4f" % data[-1, 1])
            axes[row, 0].semilogy(steps, data[:, 0], color=colour, label=label)
            for column in (1, 2, 3):
                axes[row, column].plot(steps, data[:, column], color=colour)
        axes[row, 0].axhline(TOLERANCE, color="tab:red", linewidth=0.8)
        axes[row, 0].set_ylabel("%s method\nreldV" % method)
        axes[row, 0].legend(fontsize=8)
        axes[row, 1].set_ylabel("share within 10° of a cube normal", fontsize=9)
        axes[row, 2].set_ylabel("E_ARAP")
        axes[row, 3].set_ylabel(term_name)
    for ax in axes[1]:
        ax.set_xlabel("step")
    fig.suptitle("%s: steps until reldV < %g, plain vs accelerated" % (os.path.basename(mesh), TOLERANCE))
    fig.tight_layout()
    fig.savefig(out, dpi=72)
    print("wrote", out, os.path.getsize(out), "bytes")


if __name__ == "__main__":
    main()
