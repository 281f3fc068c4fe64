"""Building a demo scene: the add-on, meshes, vertex groups, stylization.

Coordinates are read through the add-on's own mesh_io and settings are written
through its settings_io, so a scene sees and sets exactly what the add-on does.
The tests (tests/blender/helpers.py) use activate() and import_obj() from here too.
"""

import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
# Test meshes are used when present (never copied into the repo); primitives otherwise.
MESH_DIR = os.environ.get("GAUSS_MESH_DIR", os.path.join(REPO, os.pardir, "shared", "meshes"))

# The add-on package once load_addon() has run (mesh_io, settings_io, ...).
addon = None


def load_addon(build_dir):
    """Import and register the add-on staged by the build (build_dir/addon/gauss_stylization)."""
    global addon
    if addon is not None:
        return addon
    staged = os.path.join(build_dir, "addon")
    if not os.path.isfile(os.path.join(staged, "gauss_stylization", "__init__.py")):
        raise SystemExit("no staged add-on in %s: run `bash scripts/build.sh %s` first" % (staged, build_dir))
    sys.path.insert(0, staged)
    import gauss_stylization
    gauss_stylization.register()
    core = gauss_stylization.native.core()  # fail now, with the add-on's message, if the .so is wrong
    if os.environ.get("GAUSS_THREADS"):  # solver threads (default: one per core)
        core.set_num_threads(int(os.environ["GAUSS_THREADS"]))
    addon = gauss_stylization
    return addon


# -- scene -------------------------------------------------------------------------------

def reset_scene():
    """Object Mode, then remove every object and the data they used; keep the scene and its world."""
    if bpy.context.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.curves, bpy.data.cameras,
                       bpy.data.lights, bpy.data.materials):
        for block in list(collection):
            collection.remove(block)
    for child in list(bpy.context.scene.collection.children):
        bpy.data.collections.remove(child)
    # Mesh.copy() gives the copied shape keys a second user, so they outlive their mesh; Blender 4.5
    # and later refuse to save a file with such keys (an error: "invalid 'from' pointer").
    bpy.data.batch_remove([key for key in bpy.data.shape_keys if key.user is None])
    # Blender 4.x and later resync the view layer lazily: until then its objects list holds None
    # where the removed objects were.
    bpy.context.view_layer.update()


def _fcurves(animation_data):
    """The F-curves of the action ``animation_data`` plays: Action.fcurves up to Blender 4.5, the
    channelbag of the action's slot in the layered actions of 5.0 and later (Action.fcurves is gone)."""
    action = animation_data.action
    if hasattr(action, "fcurves"):
        return action.fcurves
    from bpy_extras import anim_utils
    channelbag = anim_utils.action_get_channelbag_for_slot(action, animation_data.action_slot)
    return channelbag.fcurves if channelbag is not None else []


def link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


def activate(obj):
    """Make ``obj`` the only selected object and the active one (what operators work on)."""
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    return obj


# -- meshes ------------------------------------------------------------------------------

def shared_mesh(relative_path):
    """Absolute path of a test mesh in ../shared/meshes, or None when it is not there."""
    path = os.path.join(MESH_DIR, relative_path)
    return path if os.path.isfile(path) else None


def import_obj(path, name=None):
    """Import an OBJ (Blender's importer, Y-up files become Z-up) as one mesh object, active."""
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path)
    new = [o for o in bpy.data.objects if o not in before]
    if len(new) != 1:
        raise RuntimeError("expected one object from %s, got %d" % (path, len(new)))
    obj = activate(new[0])
    if name:
        obj.name = name
    # Normals stored in the file would not follow the stylized vertices: drop them.
    if obj.data.has_custom_normals:
        bpy.ops.mesh.customdata_custom_splitnormals_clear()
    return obj


def suzanne(name="Suzanne", subdivisions=2):
    """Blender's monkey with a Subdivision Surface modifier applied (levels 2: 7958 vertices)."""
    bpy.ops.mesh.primitive_monkey_add()
    obj = bpy.context.active_object
    obj.name = name
    if subdivisions:
        modifier = obj.modifiers.new("Subdivision", 'SUBSURF')
        modifier.levels = subdivisions
        bpy.ops.object.modifier_apply(modifier=modifier.name)
    return obj


# Test meshes of ../shared/meshes used by the demos, with the rotations that stand them upright
# (after the importer's Y-up -> Z-up conversion) and turn them three-quarters to the camera.
SPOT = ("small/spot_triangulated_2930.obj", (('X', 90), ('Z', 120)))  # public domain (Keenan Crane)
BUNNY = ("bunny/bunny_odedstein_3301.obj", (('X', 90), ('Z', 20)))   # Stanford 3D Scanning Repository
BUNNY_WATERTIGHT = ("bunny/bunny_watertight_34834.obj", (('Z', 20),))  # bun_zipper, holes filled; stored Z-up
SPOT_HEAD = np.array([-math.sin(math.radians(120)), math.cos(math.radians(120)), 0.0])  # where Spot looks


def demo_mesh(which, name, size=2.0, fallback_subdivisions=1):
    """``which`` = SPOT or BUNNY: the test mesh upright, normalized and flat-shaded, or a
    subdivided Suzanne when ../shared/meshes is absent. Returns (obj, True if the test mesh)."""
    relative_path, rotations = which
    path = shared_mesh(relative_path)
    if path is not None:
        obj = import_obj(path, name)
        rotate_mesh(obj, *rotations)
    else:
        obj = suzanne(name, fallback_subdivisions)
    normalize(obj, size)
    set_flat(obj)
    return obj, path is not None


def coords(obj):
    """(#V,3) float32 vertex coordinates, object space."""
    return addon.mesh_io.read_vertex_coords(obj.data)


def enclosed_volume(co, triangles):
    """The volume a closed mesh encloses: the sum over its triangles ((#T,3) indices into the (#V,3)
    coordinates ``co``) of a . (b x c) / 6, in float64."""
    co = np.asarray(co, np.float64)
    a, b, c = (co[corner] for corner in np.asarray(triangles).T)
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6.0)


def volume(obj):
    """enclosed_volume() of ``obj``'s mesh (object space, its loop triangles)."""
    return enclosed_volume(coords(obj), addon.mesh_io.read_loop_triangles(obj.data)[0])


def normalize(obj, size=2.0):
    """Bake a transform into the mesh: largest dimension = size, centred in x/y, resting on z=0."""
    co = coords(obj)
    lo, hi = co.min(axis=0).astype(float), co.max(axis=0).astype(float)
    offset = ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2])
    obj.data.transform(Matrix.Scale(size / max(hi - lo), 4) @ Matrix.Translation([-x for x in offset]))
    obj.location = (0, 0, 0)
    obj.rotation_euler = (0, 0, 0)
    obj.scale = (1, 1, 1)
    obj.data.update()
    return obj


def rotate_mesh(obj, *rotations):
    """Bake rotations ``('X', degrees), ('Z', degrees), ...`` (applied in order) into the mesh
    data: the solver works in object space, so the style's axes are the mesh's axes."""
    for axis, degrees in rotations:
        obj.data.transform(Matrix.Rotation(math.radians(degrees), 4, axis))
    obj.data.update()


def set_flat(obj, flat=True):
    polygons = obj.data.polygons
    polygons.foreach_set("use_smooth", [not flat] * len(polygons))
    obj.data.update()


def duplicate(obj, name):
    """A copy with its own mesh and the add-on's default settings."""
    copy = obj.copy()
    copy.data = obj.data.copy()
    copy.name = copy.data.name = name
    link(copy)
    copy.property_unset("gauss_stylization")
    return copy


def vertex_group(obj, name, select):
    """Add a vertex group with weight 1 on the vertices where ``select`` ((#V,3) object-space
    coordinates -> (#V,) bool) is true. Returns their indices."""
    members = np.flatnonzero(select(coords(obj))).tolist()
    obj.vertex_groups.new(name=name).add(members, 1.0, 'REPLACE')
    return members


# -- animation ---------------------------------------------------------------------------

def bending_rig(obj, pivot, direction, bent_weights, degrees, frames):
    """Skin ``obj`` to a two-bone armature "Rig" and animate it: bone "Fixed" ends at ``pivot``, bone
    "Bent" starts there and points along ``direction``; vertex weights ``bent_weights`` ((#V,) in 0..1)
    go to "Bent", the rest to "Fixed". "Bent" turns about its own X axis (across ``direction``, level
    for a level bone), linearly from 0 degrees at frames[0] to ``degrees`` at frames[1]. Returns the rig."""
    pivot, direction = Vector(pivot), Vector(direction).normalized()
    rig = link(bpy.data.objects.new("Rig", bpy.data.armatures.new("Rig")))
    activate(rig)
    bpy.ops.object.mode_set(mode='EDIT')
    fixed = rig.data.edit_bones.new("Fixed")
    fixed.head, fixed.tail = pivot - direction, pivot
    bent = rig.data.edit_bones.new("Bent")
    bent.head, bent.tail = pivot, pivot + direction
    bent.parent = fixed
    bpy.ops.object.mode_set(mode='OBJECT')
    for name, weights in (("Fixed", 1.0 - np.asarray(bent_weights)), ("Bent", np.asarray(bent_weights))):
        group = obj.vertex_groups.new(name=name)
        for index in np.flatnonzero(weights > 0):
            group.add([int(index)], float(weights[index]), 'REPLACE')
    obj.modifiers.new("Armature", 'ARMATURE').object = rig
    bone = rig.pose.bones["Bent"]
    bone.rotation_mode = 'XYZ'
    for frame, angle in zip(frames, (0.0, degrees)):
        bone.rotation_euler = (math.radians(angle), 0.0, 0.0)
        bone.keyframe_insert("rotation_euler", frame=frame)
    for curve in _fcurves(rig.animation_data):
        for point in curve.keyframe_points:
            point.interpolation = 'LINEAR'
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = frames
    scene.frame_set(frames[0])
    activate(obj)
    return rig


def snapshot(obj, name):
    """A new static object holding ``obj`` as shown now (modifiers applied), same transform."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    mesh = bpy.data.meshes.new_from_object(obj.evaluated_get(depsgraph), preserve_all_data_layers=True,
                                           depsgraph=depsgraph)
    copy = link(bpy.data.objects.new(name, mesh))
    copy.matrix_world = obj.matrix_world
    return copy


# -- stylization -------------------------------------------------------------------------

def stylize(obj, styles, iterations=100, pin_targets="", **settings):
    """Stylize ``obj`` through the add-on's operator, as a script would.

    ``styles``: slot specs (dicts of slot fields, see settings_io.add_slot), or None to keep
    the object's slots; ``pin_targets``: the operator's (moved handles, JSON); ``settings``:
    object settings (lam, pin_group, uncovered, ...); the rest keep the add-on's defaults.
    Returns seconds spent in the operator.
    """
    settings = dict(settings, iterations=iterations)
    if styles is not None:
        settings["styles"] = styles
    addon.settings_io.apply_dict(obj.gauss_stylization, settings)
    activate(obj)
    start = time.perf_counter()
    result = bpy.ops.object.gauss_stylize(iterations=iterations, pin_targets=pin_targets)
    seconds = time.perf_counter() - start
    if result != {'FINISHED'}:
        raise RuntimeError("gauss_stylize on %s returned %s" % (obj.name, result))
    s = obj.gauss_stylization
    print("  stylized %-22s %6d vertices, %4d steps, %s lambda %g: %.2f s"
          % (obj.name, len(obj.data.vertices), iterations, s.method.lower(),
             s.cubic_lambda if s.method == 'CUBIC' else s.lam, seconds))
    return seconds
