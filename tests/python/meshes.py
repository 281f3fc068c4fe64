"""Small meshes for the module tests (numpy only); measurements are in tests/common/measures.py."""
import importlib.util
import os

import numpy as np


def _gauss_sphere():
    """The add-on's gauss_sphere.py (numpy only), loaded by path: its subdivided spheres are the
    ones the Gauss sphere overlay draws, so there is one implementation."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                        "python_addon", "gauss_stylization", "sphere", "gauss_sphere.py")
    spec = importlib.util.spec_from_file_location("gauss_sphere_for_tests", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# subdivided_sphere(V, F, levels): every triangle split in four `levels` times, new vertices on the
# unit sphere; icosphere(levels=2): a subdivided icosahedron. Both return (V float64, F int64).
_SPHERES = _gauss_sphere()
subdivided_sphere = _SPHERES.subdivided_sphere


def icosphere(levels=2):
    return _SPHERES.icosphere(levels)


def read_obj(path):
    V, F = [], []
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            V.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
            F += [(idx[0], idx[i], idx[i + 1]) for i in range(1, len(idx) - 1)]
    return np.array(V), np.array(F, dtype=np.int64)
