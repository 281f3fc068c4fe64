"""The surface of an object as the add-on's tools see it now: its coordinates and
loop triangles, and from them its face normals on the Gauss sphere.

During a live run that is the solver's current shape (whatever the output
target); otherwise the base mesh, which is what Stylize would start from (shape
keys are not mixed in).
"""

import numpy as np

from ..mesh import mesh_io
from ..run import runs
from . import directions


_triangles = {}  # mesh pointer -> (its counts and stamp, loop triangles, their polygons), least recent first
MAX_CACHED = 8


def coords_and_triangles(obj, cached_topology=False):
    """(coords #V by 3 float32, triangles #T by 3 int32) of ``obj``'s mesh now (see surface_arrays)."""
    return surface_arrays(obj, cached_topology)[:2]


def surface_arrays(obj, cached_topology=False, stamp=None):
    """(coords #V by 3 float32, triangles #T by 3 int32, polygon of each triangle #T int32) of ``obj``'s
    mesh now.

    cached_topology: reuse the triangles read last time for the same mesh with the same vertex, face
    and corner counts and the same ``stamp`` (a viewport overlay redraws far more often than artists
    change topology; the overlays pass a stamp that changes whenever the object leaves Edit Mode, where
    flips and rotated edges keep every count). One entry per mesh, the last MAX_CACHED meshes."""
    session = runs.session_of(obj)
    if session is not None:
        current = session.result if session.steps else session.arrays.coords
        return current, session.arrays.triangles, session.arrays.tri_polygon
    mesh = obj.data
    coords = np.empty((len(mesh.vertices), 3), np.float32)
    mesh_io.read_base_coords(mesh, coords)
    key = (len(mesh.vertices), len(mesh.polygons), len(mesh.loops), stamp)
    cached = _triangles.pop(mesh.as_pointer(), None)  # popped and put back: the dict keeps recent use last
    if not cached_topology or cached is None or cached[0] != key:
        cached = (key,) + tuple(mesh_io.read_loop_triangles(mesh))
    _triangles[mesh.as_pointer()] = cached
    while len(_triangles) > MAX_CACHED:
        del _triangles[next(iter(_triangles))]
    return coords, cached[1], cached[2]


def face_normals(obj):
    """Unit normals (#T by 3) and areas (#T) of the mesh's triangles, in object space."""
    return directions.triangle_normals(*coords_and_triangles(obj))


def evaluated_face_normals(obj, depsgraph):
    """Normals and areas of ``obj`` as displayed (modifiers applied), in its own space."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        coords = mesh_io.read_vertex_coords(mesh)
        triangles = mesh_io.read_loop_triangles(mesh)[0]
    finally:
        evaluated.to_mesh_clear()
    return directions.triangle_normals(coords, triangles)


def world_rotation(obj):
    """The rotation part (3 by 3) of ``obj``'s world matrix (scale and shear left out)."""
    return np.array(obj.matrix_world.to_quaternion().to_matrix(), np.float64)
