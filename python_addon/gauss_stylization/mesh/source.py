"""What a run stylizes: the object's base mesh, or the mesh as Blender shows it
(settings.use_modifiers: modifiers, armature and shape keys at the current frame).

The evaluated mesh is copied once into a mesh datablock without users (all its
layers kept: UVs, colours, custom normals, materials, vertex groups), so that
New Object output can take it over as the new object's mesh; otherwise it is
removed as soon as the run is set up (``Source.release``).
"""

import copy

import bpy
import numpy as np

from ..errors import SettingsError
from . import mesh_io


class Source:
    """The input of a run.

    arrays:        mesh_io.MeshArrays of what is stylized (coords: its rest shape)
    weights:       {vertex group name: (#V,) float32}, read from the same mesh
    evaluated:     True if arrays come from the evaluated mesh
    same_topology: the stylized mesh has the base mesh's vertices and polygons, so its result
                   can go into the base mesh or a shape key
    """

    def __init__(self, arrays, weights, evaluated, same_topology, mesh=None):
        self.arrays, self.weights = arrays, weights
        self.evaluated, self.same_topology = evaluated, same_topology
        self._mesh = mesh  # the evaluated copy while this source owns it

    def adopt_mesh(self):
        """Hand the evaluated copy over to the caller (None for the base mesh): it is no longer removed."""
        mesh, self._mesh = self._mesh, None
        return mesh

    def release(self):
        """Remove the evaluated copy unless it was adopted."""
        mesh, self._mesh = self._mesh, None
        if mesh is not None:
            bpy.data.meshes.remove(mesh)

    def moved(self, coords):
        """The same mesh with rest shape ``coords`` ((#V,3) float32): a later frame of an animation."""
        arrays = copy.copy(self.arrays)
        arrays.coords = coords
        return Source(arrays, self.weights, self.evaluated, self.same_topology)


def read(obj, use_modifiers, depsgraph=None):
    """The Source of ``obj``: its base mesh, or with ``use_modifiers`` its evaluated mesh
    (depsgraph: default the context's). Raises SettingsError if there is nothing to stylize."""
    if not use_modifiers:
        return Source(mesh_io.MeshArrays(obj.data), mesh_io.read_group_weights(obj), False, True)
    depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
    mesh = bpy.data.meshes.new_from_object(obj.evaluated_get(depsgraph), preserve_all_data_layers=True,
                                           depsgraph=depsgraph)
    try:
        if len(mesh.vertices) == 0 or len(mesh.polygons) == 0:
            raise SettingsError("'%s' has no faces after its modifiers; turn Use Modifiers off or "
                                "change the modifiers" % obj.name)
        arrays = mesh_io.MeshArrays(mesh)
        weights = mesh_io.read_group_weights(obj, mesh)
        same = same_topology(arrays, obj.data)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return Source(arrays, weights, True, same, mesh)


def same_topology(arrays, mesh):
    """Do ``mesh``'s vertices and polygons match ``arrays`` (a MeshArrays)?"""
    if len(mesh.vertices) != arrays.num_vertices or len(mesh.polygons) != arrays.num_polygons:
        return False
    corner_vertex, _, sides = mesh_io.read_corners(mesh)
    return np.array_equal(corner_vertex, arrays.corner_vertex) and np.array_equal(sides, arrays.polygon_sides)


def evaluated_coords(obj, depsgraph, arrays, what):
    """The evaluated vertex positions of ``obj`` ((#V,3) float32, object space), which must have the
    topology of ``arrays``; otherwise SettingsError saying ``what`` (e.g. "at frame 12") changed it."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        if not same_topology(arrays, mesh):
            raise SettingsError("The modifiers of '%s' change its vertices or faces %s (%d vertices instead "
                                "of %d); a point cache needs the same vertices on every frame"
                                % (obj.name, what, len(mesh.vertices), arrays.num_vertices))
        return mesh_io.read_vertex_coords(mesh)
    finally:
        evaluated.to_mesh_clear()
