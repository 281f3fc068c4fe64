"""Vertex positions in and out of a mesh (mesh_io): the fast route, and exactly what was written.

From Blender 3.5 on positions are the mesh's "position" attribute, and ``vertices.foreach_set("co")``
copies them one by one: on a 1M-vertex mesh 238 ms against 4 ms through the attribute in 4.5
(docs/performance.md#sculpt-scale), so a live tick must write through the attribute.
"""

import bmesh
import bpy
import numpy as np

import helpers


def test_positions_go_through_the_attribute_where_blender_has_one(addon):
    obj = helpers.uv_sphere()
    collection, name = addon.mesh_io.positions(obj.data)
    if bpy.app.version >= addon.mesh.mesh_io.POSITION_ATTRIBUTE_SINCE:
        assert name == "vector" and collection == obj.data.attributes["position"].data
    else:
        assert name == "co" and collection == obj.data.vertices


def test_written_positions_are_the_vertices(addon):
    mesh = helpers.uv_sphere().data
    moved = addon.mesh_io.read_vertex_coords(mesh) * np.float32(1.5) + np.float32(0.25)
    addon.mesh_io.write_vertex_coords(mesh, moved)
    mesh.update()
    seen = np.array([v.co[:] for v in mesh.vertices], np.float32)  # one by one: the reference route
    assert np.array_equal(seen, moved)
    assert np.array_equal(addon.mesh_io.read_vertex_coords(mesh), moved)
    out = np.empty_like(moved)
    addon.mesh_io.read_base_coords(mesh, out)
    assert np.array_equal(out, moved)


def _faces_read_apart(mesh_io, mesh):
    """The loop triangles and the corners, each read from Blender on its own (the reference route)."""
    return tuple(mesh_io.read_loop_triangles(mesh)) + tuple(mesh_io.read_corners(mesh))


def _triangulated(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    bm.to_mesh(obj.data)
    bm.free()
    obj.data.update()
    return obj


# Before 3.6 a polygon's loop_start was stored as given; since, Blender derives the polygons' corner
# offsets in order, and setting them out of order crashes it (bpy 4.2 to 5.3).
LOOP_STARTS_AS_GIVEN = bpy.app.version < (3, 6, 0)


def _corners_out_of_order():
    """Two quads whose corners are stored second polygon first (where LOOP_STARTS_AS_GIVEN):
    read_faces must fall back to reading the corners."""
    mesh = bpy.data.meshes.new("corners out of order")
    mesh.vertices.add(6)
    mesh.vertices.foreach_set("co", [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0])
    mesh.loops.add(8)
    mesh.loops.foreach_set("vertex_index", [0, 1, 2, 3, 1, 4, 5, 2])
    mesh.polygons.add(2)
    mesh.polygons.foreach_set("loop_start", [4, 0])
    mesh.polygons.foreach_set("loop_total", [4, 4])
    mesh.update(calc_edges=True)
    return mesh


def test_faces_read_together_are_the_triangles_and_corners_read_apart(addon):
    """read_faces derives the corners from the loop triangles (a mesh of triangles reads nothing more):
    on triangles, quads with triangle fans (the UV sphere), n-gon caps, Suzanne's mix, and a mesh
    whose polygons were taken apart and re-made (loops re-ordered), it gives what the two reads give."""
    mesh_io = addon.mesh_io
    shuffled = helpers.suzanne(levels=0)
    bm = bmesh.new()
    bm.from_mesh(shuffled.data)
    bm.faces.ensure_lookup_table()
    for face in list(bm.faces)[::3]:  # re-made faces go to the end: polygons and corners in a new order
        verts = face.verts[:]
        bm.faces.remove(face)
        bm.faces.new(verts[1:] + verts[:1])
    bm.to_mesh(shuffled.data)
    bm.free()
    meshes = {"triangles": _triangulated(helpers.uv_sphere()).data, "uv sphere": helpers.uv_sphere().data,
              "n-gon caps": helpers.capped_cylinder().data, "suzanne": helpers.suzanne(levels=1).data,
              "re-made faces": shuffled.data}
    if LOOP_STARTS_AS_GIVEN:
        meshes["corners out of order"] = _corners_out_of_order()
    for label, mesh in meshes.items():
        together, apart = mesh_io.read_faces(mesh), _faces_read_apart(mesh_io, mesh)
        assert len(together) == len(apart) == 5
        for what, a, b in zip(("triangles", "tri_polygon", "corner_vertex", "corner_polygon", "sides"),
                              together, apart):
            assert a.dtype == b.dtype and np.array_equal(a, b), (label, what)
    # On a mesh of triangles the corners are the triangles: a view of them, and corner_polygon made when
    # asked for (at 4M triangles 96 MB less for the whole run; nothing writes into these arrays).
    arrays = mesh_io.MeshArrays(meshes["triangles"])
    assert np.shares_memory(arrays.corner_vertex, arrays.triangles)
    assert np.array_equal(arrays.corner_polygon, np.repeat(np.arange(len(arrays.triangles)), 3))
    # ... and a painted weight's mean over each polygon (a Region's faces) is the same, bit for bit, as
    # the corners' sum gives on any mesh.
    weights = np.random.default_rng(3).random(arrays.num_vertices, dtype=np.float32)
    corners_sum = np.bincount(arrays.corner_polygon, weights=weights[arrays.corner_vertex], minlength=arrays.num_polygons)
    assert np.array_equal(arrays.polygon_average(weights), corners_sum / np.maximum(arrays.polygon_sides, 1))
    other = mesh_io.MeshArrays(meshes["suzanne"])
    assert not np.shares_memory(other.corner_vertex, other.triangles)
    assert np.array_equal(other.corner_polygon, _faces_read_apart(mesh_io, meshes["suzanne"])[3])
