"""Small meshes for the module tests (numpy only); measurements are in tests/common/measures.py, mesh
files are read by tests/common/mesh_files.py (read_obj is re-exported here for the tests that use it)."""
import importlib.util
import os

import numpy as np

from mesh_files import read_obj  # noqa: F401


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
