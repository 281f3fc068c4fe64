"""Where the stylized coordinates go: the mesh itself, a shape key, or a new object.

A target is set up before anything changes, then: ``prepare()`` (the first
change), ``write(coords)`` per step, and ``keep()`` or ``restore()`` at the
end. ``alive()`` says whether what it writes into still exists; ``rest`` is
(mesh, coordinates, kind) for Reset (rest_store.capture) once it is kept.
A file saved during a run holds what ``restore()`` would leave: ``hold()`` shows that
just before the file is written and ``resume(coords)`` puts the run's result back after
(coords None: the run has not written one yet).

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
import numpy as np

from ..errors import SettingsError
from ..settings import schema
from . import cache_modifier, mesh_io

SHAPE_KEY_NAME = "Gauss Stylized"
BASIS_NAME = "Basis"


def _mesh_has(mesh, num_vertices):
    """Is ``mesh`` still there with ``num_vertices`` vertices (not freed, not edited)?"""
    try:
        return len(mesh.vertices) == num_vertices
    except ReferenceError:  # freed (deleted, undo, file load)
        return False


def _write_shown_coords(mesh, coords):
    """Write ``coords`` where they show: the vertices, and with shape keys the reference key too."""
    mesh_io.write_vertex_coords(mesh, coords)
    key = mesh_io.base_key(mesh)  # looked up anew: keys may be deleted mid-run
    if key is not None:
        mesh_io.write_key_coords(key, coords)
    mesh_io.tag_changed(mesh)


class MeshTarget:
    """Move the base mesh. With shape keys the visible base is the reference
    key, so it is written too (vertices.co alone would not show)."""

    kind = 'MESH'

    def __init__(self, obj, num_vertices):
        self.mesh = obj.data
        self.num_vertices = num_vertices
        key = mesh_io.base_key(self.mesh)
        self.saved_vertices = mesh_io.read_vertex_coords(self.mesh)
        self.saved_key = None if key is None else mesh_io.read_key_coords(key, num_vertices)
        base = self.saved_vertices if self.saved_key is None else self.saved_key
        self.rest = (self.mesh, base, self.kind)

    def prepare(self):
        pass

    def write(self, coords):
        _write_shown_coords(self.mesh, coords)

    def alive(self):
        return _mesh_has(self.mesh, self.num_vertices)

    def keep(self):
        pass

    def restore(self):
        if not self.alive():  # a freed or edited mesh is left alone
            return
        mesh_io.write_vertex_coords(self.mesh, self.saved_vertices)
        key = mesh_io.base_key(self.mesh)
        if key is not None:
            # A basis added mid-run was made from the stylized shape: it gets the start shape too.
            mesh_io.write_key_coords(key, self.saved_vertices if self.saved_key is None else self.saved_key)
        mesh_io.tag_changed(self.mesh)

    def hold(self):
        self.restore()

    def resume(self, coords):
        if coords is not None:
            self.write(coords)


class ShapeKeyTarget:
    """Write into the shape key "Gauss Stylized" (relative to the basis), so the
    artist can blend the result with the key's slider. The base mesh is never moved."""

    kind = 'SHAPE_KEY'

    def __init__(self, obj, num_vertices):
        self.obj = obj
        self.mesh = obj.data
        self.num_vertices = num_vertices
        base = np.empty((num_vertices, 3), np.float32)
        mesh_io.read_base_coords(self.mesh, base)
        self.rest = (self.mesh, base, self.kind)
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

    def alive(self):
        return _mesh_has(self.mesh, self.num_vertices)

    def keep(self):
        pass

    def restore(self):
        """Put back what is still there (the artist may have deleted keys or the object meanwhile)."""
        if not self.alive():  # a freed or edited mesh is left alone
            return
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

    def hold(self):
        self.restore()

    def resume(self, coords):
        """The keys restore() removed made again (as prepare() first made them), then the result."""
        owner = self._object_using_mesh()
        active = owner.active_shape_key_index if owner is not None else None
        self.prepare()
        if coords is not None:
            self.write(coords)
        if owner is not None:
            owner.active_shape_key_index = active

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


class NewObjectTarget:
    """Write into a new object '<name>_stylized': a copy of the original (same collections,
    transform, material slots, settings) whose mesh is the stylized one. With Use Modifiers its
    mesh is the evaluated copy the source read (every layer kept) and it has no modifiers (they
    are in the mesh); otherwise its mesh is a copy of the base mesh and it keeps the modifiers.

    The original's data is never written. While a live run goes on the original is drawn as a
    wireframe, so the result can be seen through it (hiding it would leave the panel without an
    active object); keep() draws it as before but hidden and selects the new object, restore()
    removes the new object and its mesh."""

    kind = 'NEW_OBJECT'

    def __init__(self, obj, source):
        self.original = obj
        self.source = source
        self.obj = self.mesh = None
        self.num_vertices = source.arrays.num_vertices
        self.display_type = obj.display_type
        self.rest = None  # set by prepare(): (new mesh, its start coordinates, 'MESH')

    def prepare(self):
        original = self.original
        name = original.name + schema.NEW_OBJECT_SUFFIX
        mesh = self.source.adopt_mesh() or original.data.copy()
        mesh.name = name
        new = original.copy()  # settings, material slots (also object-linked ones), transform, parent
        new.data = mesh
        new.name = name
        if self.source.evaluated:
            new.modifiers.clear()  # already applied in the mesh
        else:
            cache_modifier.remove(new)  # would replay a bake over the stylized mesh
        for collection in original.users_collection:
            collection.objects.link(new)
        _select(new, False)  # linking copies the original's selection; it is selected when kept
        self.obj, self.mesh = new, mesh
        self.rest = (mesh, self.source.arrays.coords, MeshTarget.kind)
        new.display_type = self.display_type
        original.display_type = 'WIRE'

    def write(self, coords):
        _write_shown_coords(self.mesh, coords)

    def alive(self):
        try:
            return self.obj is not None and self.obj.data == self.mesh and _mesh_has(self.mesh, self.num_vertices)
        except ReferenceError:  # the new object was deleted during the run
            return False

    def keep(self):
        """The kept result takes the original's place in the view: the original is hidden (as
        Blender's own convert-to-new-object tools do), the new object selected and active."""
        self._show_original()
        _select(self.original, False)
        if _select(self.obj, True):
            bpy.context.view_layer.objects.active = self.obj
            try:
                self.original.hide_set(True)
            except (RuntimeError, ReferenceError):  # not in this view layer, or deleted during the run
                pass

    def restore(self):
        """Remove what the run created (as far as it still exists) and show the original again."""
        for block, datablocks in ((self.obj, bpy.data.objects), (self.mesh, bpy.data.meshes)):
            try:
                if block is not None:
                    datablocks.remove(block)
            except ReferenceError:  # already deleted by the artist
                pass
        self.obj = self.mesh = None
        self._show_original()

    def hold(self):
        """The new object out of every collection: an object nothing uses is not saved."""
        self.held_in = list(self.obj.users_collection)
        for collection in self.held_in:
            collection.objects.unlink(self.obj)
        self._show_original()

    def resume(self, coords):
        for collection in self.held_in:
            collection.objects.link(self.obj)
        self.held_in = []
        self.original.display_type = 'WIRE'
        if coords is not None:
            self.write(coords)

    def _show_original(self):
        try:
            self.original.display_type = self.display_type
        except ReferenceError:  # deleted during the run
            pass


def _select(obj, state):
    """Select or deselect ``obj`` in the current view layer; False if it is not in it."""
    try:
        obj.select_set(state)
    except (RuntimeError, ReferenceError):  # not in this view layer (an excluded collection), or deleted
        return False
    return True


def refusal_before_run(obj, depsgraph):
    """What the panel says before Stylize is clicked when the Output cannot take the result: Use
    Modifiers reads a mesh whose vertex or face count differs from the mesh's (make_target refuses
    it then, also for differences the counts do not show). None when nothing is known against it."""
    settings = obj.gauss_stylization
    if not settings.use_modifiers or settings.output == 'NEW_OBJECT' or not obj.modifiers:
        return None
    shown = obj.evaluated_get(depsgraph).data
    base = obj.data
    if (len(shown.vertices), len(shown.polygons)) == (len(base.vertices), len(base.polygons)):
        return None
    return ("The modifiers change the vertices or faces ({:,} vertices shown, {:,} in the mesh): the result "
            "cannot go into the {}. Choose Output: New Object, or turn Use Modifiers off").format(
        len(shown.vertices), len(base.vertices), "shape key" if settings.output == 'SHAPE_KEY' else "mesh")


def make_target(obj, source):
    """The target of ``obj``'s Output setting for a run on ``source`` (source.Source)."""
    kind = obj.gauss_stylization.output
    if kind == 'NEW_OBJECT':
        return NewObjectTarget(obj, source)
    if not source.same_topology:
        label = "shape key" if kind == 'SHAPE_KEY' else "mesh"
        raise SettingsError("The modifiers of '%s' change its vertices or faces (%d vertices shown, %d in the "
                            "mesh), so the result cannot go into its %s. Choose Output: New Object, or bake "
                            "an animation to a point cache" % (obj.name, source.arrays.num_vertices,
                                                                len(obj.data.vertices), label))
    return (ShapeKeyTarget if kind == 'SHAPE_KEY' else MeshTarget)(obj, source.arrays.num_vertices)


def target_key(obj):
    """The "Gauss Stylized" key of ``obj`` or None."""
    keys = obj.data.shape_keys
    return None if keys is None else keys.key_blocks.get(SHAPE_KEY_NAME)
