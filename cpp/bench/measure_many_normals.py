"""Measures custom-normal styles: set-up time of gauss_core.Style, time per solver
step on Spot with that style, and the accuracy of g and its gradient.

  setup/step:  python3 measure_many_normals.py time BUILD_DIR [--rounds N]
               one line per (K, sigma): median set-up seconds (wall and CPU of all threads) and median
               ms per step (wall).
  accuracy:    python3 measure_many_normals.py accuracy BUILD_DIR
               g and its gradient at 2,000 random directions against the exact Eq. 10 sum (dense
               solve over all K normals, K <= 5,856), and for 100,000 spread normals against the
               plateau g = 1 (no gradient along the sphere) that the exact sum approaches; also
               max |g(n_k) - 1|. Gradient errors are relative to sqrt(sigma), a kernel bump's slope.

Compare two builds by running both, interleaved (scripts/measure_many_normals.sh does).
Sets of normals: the cube (6), 2,000 and 100,000 random directions, Spot's 5,856 face normals.
"""
import json
import pathlib
import statistics
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
SPOT = REPO.parent / "shared" / "meshes" / "small" / "spot_triangulated_2930.obj"
SIGMAS = (4.0, 16.0, 100.0, 1000.0)


def read_obj(path):
    V, F = [], []
    for line in open(path):
        parts = line.split()
        if parts and parts[0] == "v":
            V.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
            F += [(idx[0], idx[i], idx[i + 1]) for i in range(1, len(idx) - 1)]
    return np.array(V), np.array(F, dtype=np.int64)


def random_directions(n, seed):
    D = np.random.default_rng(seed).normal(size=(n, 3))
    return D / np.linalg.norm(D, axis=1)[:, None]


def normal_sets(V, F):
    N = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    N = N[np.linalg.norm(N, axis=1) > 0]
    return {"cube": None, "2000": random_directions(2000, 1), "spot": N / np.linalg.norm(N, axis=1)[:, None],
            "100000": random_directions(100_000, 3)}


def style(gc, normals, sigma):
    return gc.Style.preset("cube", sigma=sigma) if normals is None else gc.Style(normals, sigma=sigma)


def measure_time(gc, V, F, rounds):
    sets = normal_sets(V, F)
    for name, normals in sets.items():
        for sigma in SIGMAS:
            setups, setup_cpu, steps = [], [], []
            for _ in range(rounds):
                t, c = time.perf_counter(), time.process_time()
                s = style(gc, normals, sigma)
                setups.append(time.perf_counter() - t)
                setup_cpu.append(time.process_time() - c)
            solver = gc.Solver(V, F)
            solver.set_styles([s])
            solver.step(2)
            for _ in range(rounds):
                t = time.perf_counter()
                solver.step(5)
                steps.append((time.perf_counter() - t) / 5 * 1e3)
            print(json.dumps({"set": name, "sigma": sigma, "setup_s": statistics.median(setups),
                              "setup_cpu_s": statistics.median(setup_cpu),
                              "step_ms": statistics.median(steps)}), flush=True)


def exact_g(normals, sigma, X):
    """g and its gradient at X by the exact Eq. 10: all K terms, weights from a dense solve."""
    A = np.exp(sigma * (normals @ normals.T - 1.0))
    w = np.linalg.solve(A, np.ones(len(normals)))
    E = np.exp(sigma * (X @ normals.T - 1.0)) * w
    return E.sum(axis=1), sigma * E @ normals


def measure_accuracy(gc, V, F):
    X = random_directions(2000, 99)
    small = random_directions(40, 5)  # <= 64: gauss_core sums these exactly; checks exact_g itself
    g, _ = exact_g(small, 4.0, X)
    assert np.abs(gc.Style(small, sigma=4.0).value(X) - g).max() < 1e-9
    for name, normals in normal_sets(V, F).items():
        if normals is None:
            continue
        for sigma in SIGMAS:
            s = gc.Style(normals, sigma=sigma)
            g, grad = s.value(X), s.gradient(X)
            at_inputs = float(np.abs(s.value(normals) - 1.0).max())
            if len(normals) <= 6000:
                cache = pathlib.Path("/tmp") / ("gauss_exact_g_%s_%g.npy" % (name, sigma))  # shared by builds
                if not cache.exists():
                    np.save(cache, np.column_stack(exact_g(normals, sigma, X)))
                ref = np.load(cache)
                g_ref, grad_ref = ref[:, 0], ref[:, 1:]
            else:  # the plateau: g = 1 and no gradient along the sphere (only its tangential part is compared)
                g_ref, grad_ref = np.ones(len(X)), np.sum(grad * X, axis=1)[:, None] * X
            scale = sigma ** 0.5
            print(json.dumps({"set": name, "sigma": sigma, "reference": "exact" if len(normals) <= 6000 else "plateau",
                              "max_input_error": at_inputs,
                              "g_max_abs_err": float(np.abs(g - g_ref).max()),
                              "g_median_abs_err": float(np.median(np.abs(g - g_ref))),
                              "grad_max_rel_err": float(np.linalg.norm(grad - grad_ref, axis=1).max() / scale),
                              "ref_g_range": [float(g_ref.min()), float(g_ref.max())]}), flush=True)


def main():
    mode, build = sys.argv[1], pathlib.Path(sys.argv[2])
    sys.path.insert(0, str(build / "python"))
    import gauss_core as gc
    V, F = read_obj(SPOT)
    if mode == "time":
        rounds = int(sys.argv[sys.argv.index("--rounds") + 1]) if "--rounds" in sys.argv else 3
        measure_time(gc, V, F, rounds)
    elif mode == "accuracy":
        measure_accuracy(gc, V, F)
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main()
