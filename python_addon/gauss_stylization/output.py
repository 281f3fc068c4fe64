"""Where the stylized coordinates go: the mesh itself or a shape key.

Each target snapshots exactly what it will overwrite before the first write,
so cancelling restores the mesh bit for bit (the snapshot is a float32 copy of
float32 data, written back with foreach_set).
"""

from . import mesh_io
from .validation import SettingsError

SHAPE_KEY_NAME = "Gauss Stylized"
BASIS_NAME = "Basis"


class MeshTarget:
    """Move the base mesh. With shape keys the visible base is the reference
    key, so it is written too (vertices.co alone would not show)."""

    kind = 'MESH'

    def __init__(self, obj, num_vertices):
        self.mesh = obj.data
        self.key = mesh_io.base_key(self.mesh)
        self.saved_vertices = mesh_io.read_vertex_coords(self.mesh)
        self.saved_key = None if self.key is None else mesh_io.read_key_coords(self.key, num_vertices)

    def prepare(self):
        pass

    def write(self, coords):
        mesh_io.write_vertex_coords(self.mesh, coords)
        if self.key is not None:
            mesh_io.write_key_coords(self.key, coords)
        mesh_io.tag_changed(self.mesh)

    def restore(self):
        mesh_io.write_vertex_coords(self.mesh, self.saved_vertices)
        if self.key is not None:
            mesh_io.write_key_coords(self.key, self.saved_key)
        mesh_io.tag_changed(self.mesh)


class ShapeKeyTarget:
    """Write into the shape key "Gauss Stylized" (relative to the basis), so the
    artist can blend the result with the key's slider. The base mesh is never moved."""

    kind = 'SHAPE_KEY'

    def __init__(self, obj, num_vertices):
        self.obj = obj
        self.mesh = obj.data
        keys = self.mesh.shape_keys
        if keys is not None and not keys.use_relative:
            raise SettingsError("'%s' uses absolute shape keys; turn on Relative in its "
                                "Shape Keys panel or choose Mesh output" % obj.name)
        self.had_keys = keys is not None and len(keys.key_blocks) > 0
        self.key = keys.key_blocks.get(SHAPE_KEY_NAME) if self.had_keys else None
        if self.key is not None and self.key == keys.reference_key:
            raise SettingsError("'%s' is the basis shape key of '%s'; rename it or choose "
                                "Mesh output" % (SHAPE_KEY_NAME, obj.name))
        self.had_key = self.key is not None
        self.saved_key = mesh_io.read_key_coords(self.key, num_vertices) if self.had_key else None
        self.saved_value = self.key.value if self.had_key else None
        self.saved_active = obj.active_shape_key_index

    def prepare(self):
        """Create the basis and the key if needed, and show the key fully."""
        if not self.had_keys:
            self.obj.shape_key_add(name=BASIS_NAME, from_mix=False)
        if self.key is None:
            self.key = self.obj.shape_key_add(name=SHAPE_KEY_NAME, from_mix=False)
        self.key.value = 1.0

    def write(self, coords):
        mesh_io.write_key_coords(self.key, coords)
        mesh_io.tag_changed(self.mesh)

    def restore(self):
        if self.had_key:
            mesh_io.write_key_coords(self.key, self.saved_key)
            self.key.value = self.saved_value
        else:
            self._remove_created_keys()
        self.obj.active_shape_key_index = self.saved_active
        mesh_io.tag_changed(self.mesh)

    def _remove_created_keys(self):
        if self.key is not None:
            self.obj.shape_key_remove(self.key)
            self.key = None
        if not self.had_keys and self.mesh.shape_keys is not None:
            # Removing the last key also removes the Key datablock.
            self.obj.shape_key_remove(self.mesh.shape_keys.reference_key)


def make_target(obj, num_vertices):
    kind = obj.gauss_stylization.output
    return (ShapeKeyTarget if kind == 'SHAPE_KEY' else MeshTarget)(obj, num_vertices)


def target_key(obj):
    """The "Gauss Stylized" key of ``obj`` or None."""
    keys = obj.data.shape_keys
    return None if keys is None else keys.key_blocks.get(SHAPE_KEY_NAME)
