"""Blender mesh <-> numpy arrays.

All bulk data goes through ``foreach_get``/``foreach_set`` with preallocated
float32/int32 arrays: Blender stores coordinates as float32 and indices as
int32, so these calls are plain memory copies, and nothing loops over vertices
in Python except the one-time read of vertex-group weights (Blender has no bulk
accessor for those).
"""

import bpy
import numpy as np

# From this version on Blender stores vertex positions as the mesh's "position" attribute.
POSITION_ATTRIBUTE_SINCE = (3, 5, 0)


class MeshArrays:
    """Topology and base coordinates of a mesh, read once when stylization starts.

    coords:         (#V, 3) float32, base shape (reference shape key if the mesh has keys)
    triangles:      (#T, 3) int32, loop triangles = what the solver sees
    tri_polygon:    (#T,) int32, polygon each triangle comes from
    corner_vertex / corner_polygon: (#corners,) int32, vertex and polygon of each face corner (on a
                    mesh of triangles, a view of triangles and made when asked for)
    polygon_sides:  (#P,) int32, corners per polygon
    """

    def __init__(self, mesh):
        self.num_vertices = len(mesh.vertices)
        self.num_polygons = len(mesh.polygons)
        self.coords = np.empty((self.num_vertices, 3), np.float32)
        read_base_coords(mesh, self.coords)
        (self.triangles, self.tri_polygon, self.corner_vertex, corner_polygon,
         self.polygon_sides) = read_faces(mesh)
        # On a mesh of triangles (as many triangles as polygons: a polygon has at least one) polygon p
        # is triangle p, and corner_polygon is made only when asked for: kept, it is 48 MB at 4M
        # triangles for the whole run (docs/performance.md#sculpt-scale).
        self._corner_polygon = None if len(self.tri_polygon) == self.num_polygons else corner_polygon

    @property
    def corner_polygon(self):
        if self._corner_polygon is None:
            return np.repeat(self.tri_polygon, 3)
        return self._corner_polygon

    def polygon_average(self, vertex_values):
        """Mean of a per-vertex float array over each polygon's corners."""
        if self._corner_polygon is None:  # triangles: the corners' sum in the same order, in doubles
            values = np.asarray(vertex_values, np.float64)
            return (values[self.triangles[:, 0]] + values[self.triangles[:, 1]] + values[self.triangles[:, 2]]) / 3
        sums = np.bincount(self.corner_polygon, weights=vertex_values[self.corner_vertex],
                           minlength=self.num_polygons)
        return sums / np.maximum(self.polygon_sides, 1)


def base_key(mesh):
    """The reference shape key, or None. With shape keys Blender displays the
    key data, so the base shape lives in the reference key, not in vertices.co."""
    keys = mesh.shape_keys
    return keys.reference_key if keys is not None and len(keys.key_blocks) else None


def read_base_coords(mesh, out):
    """Fill ``out`` ((#V,3) float32, C-contiguous) with the base shape."""
    key = base_key(mesh)
    if key is not None:
        key.data.foreach_get("co", out.reshape(-1))
    else:
        collection, name = positions(mesh)
        collection.foreach_get(name, out.reshape(-1))


def positions(mesh):
    """(collection, property name) of the mesh's vertex positions for foreach_get/foreach_set: the
    "position" attribute where Blender stores positions as one (3.5 and later), else the vertices.
    From 3.5 on ``vertices.foreach_set("co")`` copies vertex by vertex, 60-100 times slower than the
    attribute's one copy on a 1M-vertex mesh (docs/performance.md#sculpt-scale)."""
    attribute = mesh.attributes.get("position") if bpy.app.version >= POSITION_ATTRIBUTE_SINCE else None
    if attribute is not None and attribute.domain == 'POINT' and attribute.data_type == 'FLOAT_VECTOR':
        return attribute.data, "vector"
    return mesh.vertices, "co"


def write_vertex_coords(mesh, coords):
    collection, name = positions(mesh)
    collection.foreach_set(name, coords.reshape(-1))


def write_key_coords(key_block, coords):
    key_block.data.foreach_set("co", coords.reshape(-1))


def read_key_coords(key_block, num_vertices=None):
    out = np.empty((len(key_block.data) if num_vertices is None else num_vertices, 3), np.float32)
    key_block.data.foreach_get("co", out.reshape(-1))
    return out


def read_vertex_coords(mesh):
    out = np.empty((len(mesh.vertices), 3), np.float32)
    collection, name = positions(mesh)
    collection.foreach_get(name, out.reshape(-1))
    return out


def tag_changed(mesh):
    """Tell Blender the geometry changed (normals, depsgraph, viewport)."""
    mesh.update()


def read_loop_triangles(mesh):
    """(#T,3) int32 vertex indices of the loop triangles (what the solver sees) and
    (#T,) int32 polygon of each."""
    # Loop triangles may be stale after the mesh changed until they are computed again;
    # calc_loop_triangles() exists in every Blender the add-on supports (3.4 to 4.x).
    mesh.calc_loop_triangles()
    count = len(mesh.loop_triangles)
    triangles = np.empty((count, 3), np.int32)
    tri_polygon = np.empty(count, np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles.reshape(-1))
    mesh.loop_triangles.foreach_get("polygon_index", tri_polygon)
    return triangles, tri_polygon


def read_faces(mesh):
    """read_loop_triangles() and read_corners() together: (triangles, tri_polygon, corner_vertex,
    corner_polygon, polygon_sides), the corners derived from the loop triangles where that is exact.

    Reading the corners from Blender costs as much as reading the triangles (0.9 s against 0.7 s for
    4M triangles in 3.4; docs/performance.md#sculpt-scale), and the triangles hold them: Blender lists
    loop triangles polygon by polygon, and a triangle's in its corner order. So a mesh of triangles
    reads nothing more; other meshes read each triangle's corners (loops) and scatter, and fall back
    to read_corners() where the polygons' corners are not contiguous and in order.
    """
    mesh.calc_loop_triangles()
    num_polygons, num_loops, count = len(mesh.polygons), len(mesh.loops), len(mesh.loop_triangles)
    triangles = np.empty((count, 3), np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles.reshape(-1))
    if count == num_polygons and num_loops == 3 * count:  # a polygon has at least one triangle: all are triangles
        tri_polygon = np.arange(count, dtype=np.int32)
        return (triangles, tri_polygon, triangles.reshape(-1), np.repeat(tri_polygon, 3),
                np.full(count, 3, np.int32))
    tri_polygon = np.empty(count, np.int32)
    tri_loops = np.empty(3 * count, np.int32)
    mesh.loop_triangles.foreach_get("polygon_index", tri_polygon)
    mesh.loop_triangles.foreach_get("loops", tri_loops)
    loop_polygon = np.full(num_loops, -1, np.int32)
    loop_polygon[tri_loops] = np.repeat(tri_polygon, 3)
    if num_loops and (loop_polygon[0] < 0 or np.any(np.diff(loop_polygon) < 0)):  # -1 first if any corner is in no triangle
        return (triangles, tri_polygon) + read_corners(mesh)
    loop_vertex = np.empty(num_loops, np.int32)
    loop_vertex[tri_loops] = triangles.reshape(-1)
    sides = np.bincount(loop_polygon, minlength=num_polygons).astype(np.int32)
    return triangles, tri_polygon, loop_vertex, loop_polygon, sides


def read_corners(mesh):
    """Corner -> vertex and corner -> polygon, ordered polygon by polygon.

    Polygons normally store their corners contiguously in order, but that is
    not guaranteed, so the corner list is gathered through loop_start.
    """
    num_polygons = len(mesh.polygons)
    loop_vertex = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    loop_start = np.empty(num_polygons, np.int32)
    sides = np.empty(num_polygons, np.int32)
    mesh.polygons.foreach_get("loop_start", loop_start)
    mesh.polygons.foreach_get("loop_total", sides)
    corner_polygon = np.repeat(np.arange(num_polygons, dtype=np.int32), sides)
    first_corner = np.repeat(np.cumsum(sides) - sides, sides)
    corner_loop = np.repeat(loop_start, sides) + (np.arange(len(corner_polygon)) - first_corner)
    return loop_vertex[corner_loop], corner_polygon, sides


def read_selected_faces(obj):
    """Unit normals ((#S,3) float64) and areas ((#S,) float64) of the faces of ``obj`` selected
    now, leaving out faces without area. In Edit Mode the mesh data lag behind the edit mesh
    until the mode is left, so the edit mesh is written to them first."""
    if obj.mode == 'EDIT':
        obj.update_from_editmode()
    polygons = obj.data.polygons
    count = len(polygons)
    selected = np.zeros(count, bool)
    normals = np.empty((count, 3), np.float32)
    areas = np.empty(count, np.float32)
    polygons.foreach_get("select", selected)
    polygons.foreach_get("normal", normals.reshape(-1))
    polygons.foreach_get("area", areas)
    normals, areas = normals[selected].astype(np.float64), areas[selected].astype(np.float64)
    usable = (areas > 0) & (np.linalg.norm(normals, axis=1) > 0.5) & np.isfinite(normals).all(axis=1)
    return normals[usable], areas[usable]


def read_group_weights(obj, mesh=None):
    """{vertex group name: (#V,) float32 weights}, for every group of ``obj``, read from
    ``mesh`` (default: obj.data; an evaluated copy of it keeps the object's group numbering).

    This is the only per-vertex Python loop of the add-on; it runs once when
    stylization starts (Blender offers no bulk access to deform weights).
    """
    mesh = obj.data if mesh is None else mesh
    names = [group.name for group in obj.vertex_groups]
    weights = np.zeros((len(names), len(mesh.vertices)), np.float32)
    if names:
        rows, cols, values = [], [], []
        for vertex in mesh.vertices:
            for element in vertex.groups:
                rows.append(element.group)
                cols.append(vertex.index)
                values.append(element.weight)
        rows = np.asarray(rows, np.int64)
        valid = rows < len(names)  # stale entries of deleted groups are ignored
        weights[rows[valid], np.asarray(cols, np.int64)[valid]] = np.asarray(values, np.float32)[valid]
    return {name: weights[i] for i, name in enumerate(names)}
