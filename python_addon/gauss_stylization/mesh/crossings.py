"""Faces of a mesh that pass through each other, as the artist sees the mesh now: which polygons to
select so that a print can be checked before it is exported.

Counted on the loop triangles (what the solver sees) by ``gauss_core.self_intersections``, as Blender's
3D-Print toolbox counts them; each triangle is mapped back to the polygon it comes from.
"""

import bmesh
import bpy
import numpy as np

from .mesh_io import read_loop_triangles


class Crossings:
    """pairs:    (#P, 2) int64 loop-triangle pairs that cross (each pair once)
    polygon_pairs: (#P, 2) int32 the polygons of those triangles
    polygons: sorted (#S,) int32 indices of those polygons
    shown:    True if counted on the mesh as shown (modifiers, shape keys), False on the base mesh
              because the modifiers change its faces (their polygons could not be selected)"""

    def __init__(self, pairs, tri_polygon, shown):
        self.pairs, self.shown = pairs, shown
        self.polygon_pairs = tri_polygon[pairs].reshape(-1, 2)
        self.polygons = np.unique(self.polygon_pairs).astype(np.int32)


def _shown_coords(obj, depsgraph):
    """(#V, 3) float64 coordinates of ``obj``'s mesh as shown, or None if the modifiers change its
    vertices or faces (then the polygons shown are not the mesh's own)."""
    mesh = obj.data
    evaluated = obj.evaluated_get(depsgraph)
    shown = evaluated.to_mesh()
    try:
        if len(shown.vertices) != len(mesh.vertices) or len(shown.polygons) != len(mesh.polygons):
            return None
        coords = np.empty((len(shown.vertices), 3), np.float32)
        shown.vertices.foreach_get("co", coords.reshape(-1))
        return coords.astype(np.float64)
    finally:
        evaluated.to_mesh_clear()


def find(gauss_core, obj, depsgraph):
    """The Crossings of ``obj``'s mesh in Object Mode (call obj.update_from_editmode() first in Edit
    Mode: the edit mesh is checked by its base coordinates, which are what Edit Mode shows)."""
    mesh = obj.data
    coords = None if obj.mode == 'EDIT' else _shown_coords(obj, depsgraph)
    shown = coords is not None or obj.mode == 'EDIT'
    if coords is None:
        coords = np.empty((len(mesh.vertices), 3), np.float32)
        mesh.vertices.foreach_get("co", coords.reshape(-1))
        coords = coords.astype(np.float64)
    triangles, tri_polygon = read_loop_triangles(mesh)
    if not len(triangles):
        return Crossings(np.empty((0, 2), np.int64), tri_polygon, shown)
    pairs = np.asarray(gauss_core.self_intersections(coords, triangles), np.int64).reshape(-1, 2)
    return Crossings(pairs, tri_polygon, shown)


def select_polygons(mesh, polygons):
    """Select exactly ``polygons`` of ``mesh`` (Object Mode data), with their edges and vertices, so
    that Edit Mode shows them selected."""
    count = len(mesh.polygons)
    chosen = np.zeros(count, bool)
    chosen[polygons] = True
    loop_start = np.empty(count, np.int32)
    sides = np.empty(count, np.int32)
    mesh.polygons.foreach_get("loop_start", loop_start)
    mesh.polygons.foreach_get("loop_total", sides)
    loop_vertex = np.empty(len(mesh.loops), np.int32)
    loop_edge = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    mesh.loops.foreach_get("edge_index", loop_edge)
    loops = np.concatenate([np.arange(s, s + n) for s, n in zip(loop_start[chosen], sides[chosen])]) \
        if chosen.any() else np.empty(0, np.int64)
    vertices = np.zeros(len(mesh.vertices), bool)
    vertices[loop_vertex[loops]] = True
    edges = np.zeros(len(mesh.edges), bool)
    edges[loop_edge[loops]] = True
    mesh.vertices.foreach_set("select", vertices)
    mesh.edges.foreach_set("select", edges)
    mesh.polygons.foreach_set("select", chosen)
    mesh.update()


def polygons_with_vertices(arrays, vertices):
    """Sorted (#S,) int32 indices of the polygons of ``arrays`` (a MeshArrays) with a corner at any of
    ``vertices``."""
    at = np.zeros(arrays.num_vertices, bool)
    at[np.asarray(vertices, np.int64)] = True
    return np.unique(arrays.corner_polygon[at[arrays.corner_vertex]]).astype(np.int32)


def select_and_show(context, obj, polygons, running):
    """Select exactly ``polygons`` of ``obj`` and show them: in Edit Mode, which an object in Object
    Mode enters when something is selected, unless a live run goes on (``running``: Edit Mode would end
    it, so then it waits for the artist)."""
    if obj.mode == 'EDIT':
        _select_in_edit_mode(context, obj, polygons)
        return
    select_polygons(obj.data, polygons)
    if len(polygons) and not running and context.window is not None:
        bpy.ops.object.mode_set(mode='EDIT')
        # In vertex select mode Edit Mode would add every face whose corners are all selected.
        _select_in_edit_mode(context, obj, polygons)


def _select_in_edit_mode(context, obj, polygons):
    mesh = obj.data
    context.tool_settings.mesh_select_mode = (False, False, True)
    edit = bmesh.from_edit_mesh(mesh)
    for element in (*edit.verts, *edit.edges, *edit.faces):
        element.select_set(False)
    edit.faces.ensure_lookup_table()
    for index in polygons:
        edit.faces[int(index)].select_set(True)
    edit.select_flush_mode()
    bmesh.update_edit_mesh(mesh)
