"""Vertex positions in and out of a mesh (mesh_io): the fast route, and exactly what was written.

From Blender 3.5 on positions are the mesh's "position" attribute, and ``vertices.foreach_set("co")``
copies them one by one: on a 1M-vertex mesh 238 ms against 4 ms through the attribute in 4.5
(docs/performance.md#sculpt-scale), so a live tick must write through the attribute.
"""

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
