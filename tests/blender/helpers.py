"""Scene building and measuring helpers shared by the Blender tests.

Meshes are read and settings written through the add-on's own mesh_io and
settings_io, so a test sees and sets exactly what the add-on does; activate()
and import_obj() are the demo scenes' (blender_scenes/scene_kit.py), the
aligned-share measure the module tests' (tests/common/measures.py).
"""

import os
import sys
import time

import bmesh
import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MESHES = os.path.join(REPO, "..", "shared", "meshes")
BUILD = os.path.abspath(os.environ.get("GAUSS_BUILD_DIR", os.path.join(REPO, "build")))
# The folder holding the gauss_stylization package under test: the build's staged add-on, or where
# Blender installed it (GAUSS_ADDON_DIR, set by scripts/test_blender_versions.sh).
ADDON_DIR = os.path.abspath(os.environ.get("GAUSS_ADDON_DIR", os.path.join(BUILD, "addon")))
if not os.path.isdir(os.path.join(ADDON_DIR, "gauss_stylization")):
    raise ImportError("no add-on in %s: build the project first (bash scripts/build.sh)" % ADDON_DIR)
for _path in (ADDON_DIR, os.path.join(REPO, "tests", "common"),
              os.path.join(REPO, "blender_scenes")):
    if _path not in sys.path:
        sys.path.insert(0, _path)

# Importing does not register the add-on.
from gauss_stylization import mesh_io, settings_io  # noqa: E402
from gauss_stylization.run import live_run as _live_run, targets  # noqa: E402
from measures import aligned_share as _aligned_share  # noqa: E402
import scene_kit  # noqa: E402
from scene_kit import activate  # noqa: E402,F401  (part of this module's API)

AXES = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)

clear_scene = scene_kit.reset_scene


def object_from_bmesh(bm, name):
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return activate(obj)


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


def capped_cylinder():
    """The capped 32-sided cylinder of tests/common/flat_meshes.py (two large flat regions), active."""
    from flat_meshes import capped_cylinder as make
    V, F = make()
    mesh = bpy.data.meshes.new("Cylinder")
    mesh.from_pydata(V.tolist(), [], F.tolist())
    obj = bpy.data.objects.new("Cylinder", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return activate(obj)


def import_obj(relative):
    """A mesh of ../shared/meshes, imported and active."""
    return scene_kit.import_obj(os.path.join(MESHES, relative))


def coords(obj):
    return mesh_io.read_vertex_coords(obj.data)


mesh_coords = mesh_io.read_vertex_coords
key_coords = mesh_io.read_key_coords


def evaluated_coords(obj):
    """Vertex positions as displayed (shape keys mixed in), object space."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    out = mesh_io.read_vertex_coords(evaluated.to_mesh())
    evaluated.to_mesh_clear()
    return out


def triangles(obj):
    """The loop triangles the solver sees and the polygon of each (mesh_io.read_loop_triangles)."""
    return mesh_io.read_loop_triangles(obj.data)


def aligned_share(obj, directions, positions=None, triangle_mask=None, degrees=10.0):
    """Area-weighted share of the surface whose normal is within ``degrees`` of a direction."""
    positions = coords(obj) if positions is None else positions
    return _aligned_share(positions, triangles(obj)[0], directions, degrees, triangle_mask)


def crossing_pairs(obj):
    """Pairs of the object's triangles that cross, counted as Blender's 3D-Print toolbox counts them:
    a BVHTree of the triangulated mesh overlapped with itself (each pair once)."""
    from mathutils.bvhtree import BVHTree
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    tree = BVHTree.FromBMesh(bm)
    pairs = {tuple(sorted(pair)) for pair in tree.overlap(tree)}
    bm.free()
    return len(pairs)


def add_group(obj, name, indices, weight=1.0):
    group = obj.vertex_groups.new(name=name)
    group.add([int(i) for i in indices], weight, 'REPLACE')
    return group


def save_as_version(addon, path, version, *fields):
    """Write the file as the add-on at settings version ``version`` wrote it: the stamp ``version`` (0:
    none), and the ``fields`` never set, as no earlier version knew them (settings/versioning.py)."""
    versioning = addon.settings.versioning
    for obj in bpy.data.objects:
        settings = obj.gauss_stylization
        for field in fields:
            settings.property_unset(field)
        if version:
            settings.settings_version = version
        else:
            settings.property_unset(versioning.STAMP)
    versioning.unregister_handlers()
    try:
        bpy.ops.wm.save_as_mainfile(filepath=path)
    finally:
        versioning.register_handlers()


def replays_with_the_old_rule(addon, make_object, field, steps):
    """Asserts that Replay of a kept run whose recipe predates ``field`` (a Bool keeping an old rule,
    settings/versioning.py) uses the rule it ran with (``field`` on), whatever the object says now, and
    leaves the object's ``field`` as it was. ``make_object()`` makes the object, style slots and all."""
    today = make_object()
    activate(today)
    assert stylize(steps) == {'FINISHED'}
    todays_result = coords(today)
    clear_scene()
    obj = make_object()
    activate(obj)
    setattr(obj.gauss_stylization, field, True)  # the rule an older object ran with
    assert stylize(steps) == {'FINISHED'}
    kept = coords(obj)
    # So the replay below tells the rules apart (by more than two separately built objects may differ).
    assert np.abs(kept - todays_result).max() > 1e-4
    store = addon.mesh.recipe_store
    recipe = store.load(obj.data)
    for run in recipe["runs"]:
        assert run["settings"].pop(field) is True  # as the older version recorded it: without the field
    store.save(obj.data, recipe)
    setattr(obj.gauss_stylization, field, False)  # today's rule on the object
    activate(obj)
    assert bpy.ops.object.gauss_replay() == {'FINISHED'}
    assert np.array_equal(coords(obj), kept)
    assert getattr(obj.gauss_stylization, field) is False  # the artist's setting is left as it was


def stepped_result(addon, obj, steps=8):
    """The coordinates a session of ``obj`` reaches in ``steps`` steps; the session is cancelled, so the
    mesh is as it was."""
    run = addon.run.session.Session(obj)
    run.step(steps)
    out = coords(obj)
    run.cancel()
    return out


def stylize(iterations, **settings):
    """Run the operator as a script would (execute, no invoke) after setting object ``settings``."""
    settings_io.apply_dict(bpy.context.active_object.gauss_stylization, settings)
    return bpy.ops.object.gauss_stylize(iterations=iterations)


def add_slot(obj, preset='CUBE', group="", name=None, **values):
    """A new style slot (settings_io.add_slot); unnamed slots are called after their preset."""
    spec = dict(values, preset=preset, vertex_group=group)
    if name:
        spec["name"] = name
    return settings_io.add_slot(obj.gauss_stylization, spec)


class Reports:
    """Where an operator's reports go when a test plans a run itself: lines [(kind, text)]."""

    def __init__(self):
        self.lines = []

    def report(self, kind, text):
        self.lines.append((kind, text))


def live_run(objects, limit=60.0):
    """A live_run.LiveRun of ``objects`` (as the modal operator starts it) with its set-up done
    and every object in it; the tests call tick() themselves."""
    live = _live_run.LiveRun(targets.plan_objects(Reports(), objects))
    deadline = time.monotonic() + limit
    while not live.setup.done and time.monotonic() < deadline:
        time.sleep(0.01)
    assert live.finish_setup() == []
    return live


def live_run_with_a_repaint(obj, group, weight, ticks_before, ticks_after):
    """A live run of ``obj`` in which the artist, after ``ticks_before`` ticks, paints every vertex of
    ``group`` to ``weight`` in Weight Paint mode (the run reads the strokes on the way back to Object
    Mode), then ``ticks_after`` ticks more. Returns the run, not yet kept."""
    live = live_run([obj])
    try:
        for _ in range(ticks_before):
            live.tick(budget=1e9)
        bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
        obj.vertex_groups[group].add(list(range(len(obj.data.vertices))), weight, 'REPLACE')  # the strokes
        live.tick(budget=1e9)
        bpy.ops.object.mode_set(mode='OBJECT')
        for _ in range(ticks_after):
            live.tick(budget=1e9)
    finally:
        if obj.mode != 'OBJECT':
            bpy.ops.object.mode_set(mode='OBJECT')
    return live
