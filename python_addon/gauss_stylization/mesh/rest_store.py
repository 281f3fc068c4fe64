"""The coordinates captured when a stylization started, kept in the .blend.

They are stored as hidden ID properties of the mesh (names starting with "_"
are not shown in the Custom Properties panel): a float32 array of the base
coordinates and the output the run wrote to. They survive saving, reopening
and undo, and are read back as numbers only (no eval).
"""

import numpy as np

from ..errors import SettingsError
from . import mesh_io, recipe_store
from .output import target_key

COORDS = "_gauss_rest_co"
TARGET = "_gauss_rest_target"


def capture(mesh, coords, target_kind):
    mesh[COORDS] = np.ascontiguousarray(coords, np.float32).reshape(-1)
    mesh[TARGET] = target_kind


def has_capture(mesh):
    return COORDS in mesh


def _captured_coords(mesh):
    stored = mesh[COORDS]
    values = np.array(stored, dtype=np.float32).reshape(-1)
    if values.size != 3 * len(mesh.vertices):
        raise SettingsError("The mesh's vertex count changed since it was stylized; "
                            "it cannot be reset any more")
    return values.reshape(-1, 3)


def restore(obj):
    """Write the captured coordinates back where the last stylization wrote; that run leaves the
    mesh's recipe (recipe_store.py) if it was still there."""
    mesh = obj.data
    if not has_capture(mesh):
        raise SettingsError("'%s' has not been stylized yet; nothing to reset" % obj.name)
    coords = _captured_coords(mesh)
    if mesh.get(TARGET) == 'SHAPE_KEY':
        key = target_key(obj)
        if key is None:
            raise SettingsError("The shape key 'Gauss Stylized' was removed; nothing to reset")
        recipe_store.drop_last_run(mesh, mesh_io.read_key_coords(key))
        mesh_io.write_key_coords(key, coords)
    else:
        now = np.empty((len(mesh.vertices), 3), np.float32)
        mesh_io.read_base_coords(mesh, now)
        recipe_store.drop_last_run(mesh, now)
        mesh_io.write_vertex_coords(mesh, coords)
        base = mesh_io.base_key(mesh)
        if base is not None:
            mesh_io.write_key_coords(base, coords)
    mesh_io.tag_changed(mesh)
