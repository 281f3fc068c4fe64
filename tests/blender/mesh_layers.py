"""Everything a mesh holds besides its vertex positions, as comparable numpy arrays.

For checking that an output keeps UVs, colour attributes, custom split normals,
materials, polygons, edges, vertex groups and every other attribute.
"""

import bmesh
import bpy
import numpy as np

# Attribute data type -> (foreach key, components, numpy dtype).
_ATTRIBUTE_READ = {
    'FLOAT': ("value", 1, np.float32), 'INT': ("value", 1, np.int32), 'INT8': ("value", 1, np.int32),
    'BOOLEAN': ("value", 1, bool), 'FLOAT_VECTOR': ("vector", 3, np.float32),
    'FLOAT2': ("vector", 2, np.float32), 'FLOAT_COLOR': ("color", 4, np.float32),
    'BYTE_COLOR': ("color", 4, np.float32), 'INT32_2D': ("value", 2, np.int32),
    'INT16_2D': ("value", 2, np.int32),  # custom normals, Blender 4.1 and later
    'QUATERNION': ("value", 4, np.float32),
}
_DOMAIN_SIZE = {'POINT': "vertices", 'EDGE': "edges", 'FACE': "polygons", 'CORNER': "loops"}


def _get(collection, key, components, dtype):
    out = np.empty(len(collection) * components, dtype)
    collection.foreach_get(key, out)
    return out


def _attributes(mesh):
    found = {}
    for attribute in mesh.attributes:
        if attribute.name == "position" or attribute.data_type == 'STRING':
            continue
        key, components, dtype = _ATTRIBUTE_READ[attribute.data_type]
        found["attribute %s (%s %s)" % (attribute.name, attribute.domain, attribute.data_type)] = \
            _get(attribute.data, key, components, dtype)
    return found


def loop_normals(mesh):
    """(#loops, 3) split normals, custom ones included (Blender 3.4 .. 4.x)."""
    if hasattr(mesh, "corner_normals"):  # 4.1+
        return _get(mesh.corner_normals, "vector", 3, np.float32)
    mesh.calc_normals_split()
    return _get(mesh.loops, "normal", 3, np.float32)


def layers(obj, mesh=None):
    """{what: array or value} of ``mesh`` (default obj.data) except the positions."""
    mesh = obj.data if mesh is None else mesh
    found = {
        "counts": (len(mesh.vertices), len(mesh.edges), len(mesh.polygons), len(mesh.loops)),
        "edges": _get(mesh.edges, "vertices", 2, np.int32),
        "loop vertices": _get(mesh.loops, "vertex_index", 1, np.int32),
        "loop edges": _get(mesh.loops, "edge_index", 1, np.int32),
        "polygon starts": _get(mesh.polygons, "loop_start", 1, np.int32),
        "polygon sides": _get(mesh.polygons, "loop_total", 1, np.int32),
        "material indices": _get(mesh.polygons, "material_index", 1, np.int32),
        "smooth": _get(mesh.polygons, "use_smooth", 1, bool),
        "seams": _get(mesh.edges, "use_seam", 1, bool),
        "materials": [m.name if m else None for m in mesh.materials],
        "object materials": [slot.material.name if slot.material else None for slot in obj.material_slots],
        "custom normals": mesh.has_custom_normals,
        "split normals": loop_normals(mesh),
        "vertex groups": [g.name for g in obj.vertex_groups],
        "weights": _weights(obj, mesh),
    }
    for layer in mesh.uv_layers:
        found["uv %s" % layer.name] = _get(layer.data, "uv", 2, np.float32)
    found.update(_attributes(mesh))
    return found


def _weights(obj, mesh):
    out = np.zeros((len(obj.vertex_groups), len(mesh.vertices)), np.float32)
    for vertex in mesh.vertices:
        for element in vertex.groups:
            if element.group < len(out):
                out[element.group, vertex.index] = element.weight
    return out


def differences(before, after):
    """Names of the entries that differ (bit for bit)."""
    names = sorted(set(before) | set(after))
    return [name for name in names if name not in before or name not in after
            or not np.array_equal(np.asarray(before[name]), np.asarray(after[name]))]


def decorated_suzanne(name="Decorated"):
    """Suzanne with a UV map, a corner colour attribute, a float point attribute, custom split
    normals, two materials on alternate polygons, a vertex group and seams."""
    bm = bmesh.new()
    bm.loops.layers.uv.new("UVMap")
    bmesh.ops.create_monkey(bm, calc_uvs=True)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    rng = np.random.default_rng(7)
    colours = mesh.color_attributes.new("Paint", 'BYTE_COLOR', 'CORNER')
    colours.data.foreach_set("color", rng.random(4 * len(mesh.loops)).astype(np.float32))
    heat = mesh.attributes.new("heat", 'FLOAT', 'POINT')
    heat.data.foreach_set("value", rng.random(len(mesh.vertices)).astype(np.float32))
    for material in ("Red", "Blue"):
        mesh.materials.append(bpy.data.materials.new(material))
    mesh.polygons.foreach_set("material_index", (np.arange(len(mesh.polygons)) % 2).astype(np.int32))
    mesh.polygons.foreach_set("use_smooth", np.ones(len(mesh.polygons), bool))
    mesh.edges.foreach_set("use_seam", (np.arange(len(mesh.edges)) % 3 == 0))
    if hasattr(mesh, "use_auto_smooth"):  # needed for custom normals before Blender 4.1
        mesh.use_auto_smooth = True
    normals = rng.normal(size=(len(mesh.loops), 3))
    mesh.normals_split_custom_set((normals / np.linalg.norm(normals, axis=1)[:, None]).tolist())
    group = obj.vertex_groups.new(name="Left")
    group.add([v.index for v in mesh.vertices if v.co.x < 0], 0.75, 'REPLACE')
    mesh.update()
    return obj
