"""Scene building and measuring helpers shared by the Blender tests."""

import math
import os

import bmesh
import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MESHES = os.path.join(REPO, "..", "shared", "meshes")

AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)


def clear_scene():
    if bpy.context.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for mesh in list(bpy.data.meshes):
        bpy.data.meshes.remove(mesh)


def activate(obj):
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def object_from_bmesh(bm, name):
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    activate(obj)
    return obj


def suzanne(levels=1):
    """Suzanne, Catmull-Clark subdivided ``levels`` times (all quads)."""
    bm = bmesh.new()
    bmesh.ops.create_monkey(bm)
    obj = object_from_bmesh(bm, "Suzanne")
    if levels:
        modifier = obj.modifiers.new("Subdivision", 'SUBSURF')
        modifier.levels = levels
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        old = obj.data
        obj.data = bpy.data.meshes.new_from_object(evaluated)
        obj.modifiers.clear()
        bpy.data.meshes.remove(old)
    return obj


def uv_sphere(segments=32, rings=16):
    bm = bmesh.new()
    bmesh.ops.create_uvsphere(bm, u_segments=segments, v_segments=rings, radius=1.0)
    return object_from_bmesh(bm, "Sphere")


def import_obj(relative):
    bpy.ops.wm.obj_import(filepath=os.path.join(MESHES, relative))
    obj = bpy.context.selected_objects[0]
    activate(obj)
    return obj


def coords(obj):
    return mesh_coords(obj.data)


def mesh_coords(mesh):
    out = np.empty((len(mesh.vertices), 3), np.float32)
    mesh.vertices.foreach_get("co", out.reshape(-1))
    return out


def key_coords(key):
    out = np.empty((len(key.data), 3), np.float32)
    key.data.foreach_get("co", out.reshape(-1))
    return out


def evaluated_coords(obj):
    """Vertex positions as displayed (shape keys mixed in), object space."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    out = np.empty((len(mesh.vertices), 3), np.float32)
    mesh.vertices.foreach_get("co", out.reshape(-1))
    evaluated.to_mesh_clear()
    return out


def triangles(obj):
    mesh = obj.data
    if hasattr(mesh, "calc_loop_triangles"):  # Blender < 4.1; newer ones compute on demand
        mesh.calc_loop_triangles()
    tris = np.empty((len(mesh.loop_triangles), 3), np.int32)
    mesh.loop_triangles.foreach_get("vertices", tris.reshape(-1))
    tri_polygon = np.empty(len(tris), np.int32)
    mesh.loop_triangles.foreach_get("polygon_index", tri_polygon)
    return tris, tri_polygon


def aligned_share(obj, directions, positions=None, triangle_mask=None, degrees=10.0):
    """Area-weighted share of the surface whose normal is within ``degrees`` of a direction."""
    positions = coords(obj) if positions is None else positions
    tris, _ = triangles(obj)
    p = positions.astype(np.float64)
    cross = np.cross(p[tris[:, 1]] - p[tris[:, 0]], p[tris[:, 2]] - p[tris[:, 0]])
    area = np.linalg.norm(cross, axis=1)
    normals = cross / np.maximum(area, 1e-30)[:, None]
    dirs = np.asarray(directions, float)
    dirs = dirs / np.linalg.norm(dirs, axis=1)[:, None]
    aligned = (normals @ dirs.T).max(axis=1) > math.cos(math.radians(degrees))
    if triangle_mask is not None:
        area, aligned = area[triangle_mask], aligned[triangle_mask]
    return float(area[aligned].sum() / area.sum())


def add_group(obj, name, indices, weight=1.0):
    group = obj.vertex_groups.new(name=name)
    group.add([int(i) for i in indices], weight, 'REPLACE')
    return group


def stylize(iterations, **settings):
    """Run the operator as a script would (execute, no invoke)."""
    obj = bpy.context.active_object
    for name, value in settings.items():
        setattr(obj.gauss_stylization, name, value)
    return bpy.ops.object.gauss_stylize(iterations=iterations)


def add_slot(obj, preset='CUBE', group="", name=None, **values):
    slot = obj.gauss_stylization.styles.add()
    slot.name = name or preset.title()
    slot.preset = preset
    slot.vertex_group = group
    for key, value in values.items():
        setattr(slot, key, value)
    return slot
