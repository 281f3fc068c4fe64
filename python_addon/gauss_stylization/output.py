"""Where the stylized coordinates go: the mesh itself or a shape key.

Each target snapshots exactly what it will overwrite before the first write,
so cancelling restores the mesh bit for bit (the snapshot is a float32 copy of
float32 data, written back with foreach_set).

Targets keep only ID references (the object and the mesh) between ticks and
look shape keys up again at every use: the panel stays usable during a live
run, so the artist can delete shape keys (or the object) meanwhile. Python
notices a freed ID (ReferenceError), but a freed KeyBlock would be a dangling
pointer, and writing through it crashed Blender.
"""

import bpy

from . import mesh_io
from .errors import SettingsError

SHAPE_KEY_NAME = "Gauss Stylized"
BASIS_NAME = "Basis"


class MeshTarget:
    """Move the base mesh. With shape keys the visible base is the reference
    key, so it is written too (vertices.co alone would not show)."""

    kind = 'MESH'

    def __init__(self, obj, num_vertices):
        self.mesh = obj.data
        key = mesh_io.base_key(self.mesh)
        self.saved_vertices = mesh_io.read_vertex_coords(self.mesh)
        self.saved_key = None if key is None else mesh_io.read_key_coords(key, num_vertices)

    def prepare(self):
        pass

    def write(self, coords):
        mesh_io.write_vertex_coords(self.mesh, coords)
        key = mesh_io.base_key(self.mesh)  # looked up anew: keys may be deleted mid-run
        if key is not None:
            mesh_io.write_key_coords(key, coords)
        mesh_io.tag_changed(self.mesh)

    def restore(self):
        mesh_io.write_vertex_coords(self.mesh, self.saved_vertices)
        key = mesh_io.base_key(self.mesh)
        if key is not None:
            # A basis added mid-run was made from the stylized shape: it gets the start shape too.
            mesh_io.write_key_coords(key, self.saved_vertices if self.saved_key is None else self.saved_key)
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
        key = self._key()
        if key is not None and key == keys.reference_key:
            raise SettingsError("'%s' is the basis shape key of '%s'; rename it or choose "
                                "Mesh output" % (SHAPE_KEY_NAME, obj.name))
        self.had_key = key is not None
        self.saved_key = mesh_io.read_key_coords(key, num_vertices) if self.had_key else None
        self.saved_value = key.value if self.had_key else None
        self.saved_active = obj.active_shape_key_index

    def _key(self):
        """The "Gauss Stylized" key of the mesh now (never a KeyBlock kept from an earlier tick)."""
        keys = self.mesh.shape_keys
        return None if keys is None else keys.key_blocks.get(SHAPE_KEY_NAME)

    def prepare(self):
        """Create the basis and the key if needed, and show the key fully."""
        if not self.had_keys:
            self.obj.shape_key_add(name=BASIS_NAME, from_mix=False)
        key = self._key()
        if key is None:
            key = self.obj.shape_key_add(name=SHAPE_KEY_NAME, from_mix=False)
        key.value = 1.0

    def write(self, coords):
        key = self._key()
        if key is None:
            raise SettingsError("The shape key '%s' was deleted or renamed while Stylize was running"
                                % SHAPE_KEY_NAME)
        mesh_io.write_key_coords(key, coords)
        mesh_io.tag_changed(self.mesh)

    def restore(self):
        """Put back what is still there (the artist may have deleted keys or the object meanwhile)."""
        key = self._key()
        if self.had_key:
            if key is not None:
                mesh_io.write_key_coords(key, self.saved_key)
                key.value = self.saved_value
        else:
            self._remove_created_keys(key)
        if self._object_using_mesh() is not None:
            self.obj.active_shape_key_index = self.saved_active
        mesh_io.tag_changed(self.mesh)

    def _object_using_mesh(self):
        try:
            return self.obj if self.obj.data == self.mesh else None
        except ReferenceError:  # the object was deleted during the run
            return None

    def _remove_created_keys(self, key):
        # Only Object.shape_key_remove removes keys. If the object was deleted
        # (or given another mesh) during the run, a temporary object lends it.
        owner = self._object_using_mesh()
        borrowed = None
        if owner is None:
            owner = borrowed = bpy.data.objects.new("Gauss Stylize restore", self.mesh)
        try:
            if key is not None:
                owner.shape_key_remove(key)
            if not self.had_keys and self.mesh.shape_keys is not None:
                # Removing the last key also removes the Key datablock.
                owner.shape_key_remove(self.mesh.shape_keys.reference_key)
        finally:
            if borrowed is not None:
                bpy.data.objects.remove(borrowed)


def make_target(obj, num_vertices):
    kind = obj.gauss_stylization.output
    return (ShapeKeyTarget if kind == 'SHAPE_KEY' else MeshTarget)(obj, num_vertices)


def target_key(obj):
    """The "Gauss Stylized" key of ``obj`` or None."""
    keys = obj.data.shape_keys
    return None if keys is None else keys.key_blocks.get(SHAPE_KEY_NAME)
