"""Shared helpers of the demo scenes: arguments, add-on loading, meshes, stylization,
layout, labels, camera, light, Workbench render settings, saving.

Every scene module defines ``NAME`` (output file stem) and ``build()`` (fills the empty
scene). A scene can run on its own:

    blender -b --factory-startup --python-exit-code 1 -P blender_scenes/scene_styles.py -- BUILD_DIR OUT_DIR

or all together through ``render_all.py``. Works with Blender 3.4 and 4.x (Workbench
render engine only, no bgl, no EEVEE/Cycles specifics).
"""

import math
import os
import sys
import time

import bpy
from mathutils import Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
# Test meshes are used when present (never copied into the repo); primitives otherwise.
MESH_DIR = os.environ.get("GAUSS_MESH_DIR", os.path.join(REPO, os.pardir, "shared", "meshes"))

RESOLUTION = (480, 360)
BACKGROUND = (0.93, 0.93, 0.95)
ORIGINAL_COLOR = (0.62, 0.64, 0.68, 1.0)   # grey: the unchanged input
STYLIZED_COLOR = (0.86, 0.55, 0.30, 1.0)   # warm: the stylized result
SECOND_COLOR = (0.33, 0.56, 0.82, 1.0)     # blue: a second style region
PIN_COLOR = (0.85, 0.20, 0.20, 1.0)
LABEL_COLOR = (0.12, 0.12, 0.14, 1.0)


# -- arguments and the add-on ------------------------------------------------------------

def script_args():
    """Arguments after ``--`` on Blender's command line."""
    argv = sys.argv
    return argv[argv.index("--") + 1:] if "--" in argv else []


def parse_build_out(args, usage):
    """``BUILD_DIR OUT_DIR`` (both made absolute against the current directory)."""
    if len(args) < 2:
        raise SystemExit("usage: " + usage)
    return os.path.abspath(args[0]), os.path.abspath(args[1])


_loaded = False


def load_addon(build_dir):
    """Import and register the add-on staged by the build (build_dir/addon/gauss_stylization)."""
    global _loaded
    if _loaded:
        return
    staged = os.path.join(build_dir, "addon")
    if not os.path.isfile(os.path.join(staged, "gauss_stylization", "__init__.py")):
        raise SystemExit("no staged add-on in %s: run `bash scripts/build.sh %s` first" % (staged, build_dir))
    sys.path.insert(0, staged)
    import gauss_stylization
    gauss_stylization.register()
    core = gauss_stylization.native.core()  # fail now, with the add-on's message, if the .so is wrong
    if os.environ.get("GAUSS_THREADS"):  # solver threads (default: one per core)
        core.set_num_threads(int(os.environ["GAUSS_THREADS"]))
    _loaded = True


# -- scene -------------------------------------------------------------------------------

def reset_scene():
    """Remove every object and the data they used; keep the scene and its world."""
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.curves, bpy.data.cameras,
                       bpy.data.lights, bpy.data.materials):
        for block in list(collection):
            collection.remove(block)
    scene = bpy.context.scene
    for child in list(scene.collection.children):
        bpy.data.collections.remove(child)


def _link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


def activate(obj):
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


# -- meshes ------------------------------------------------------------------------------

def shared_mesh(relative_path):
    """Absolute path of a test mesh in ../shared/meshes, or None when it is not there."""
    path = os.path.join(MESH_DIR, relative_path)
    return path if os.path.isfile(path) else None


def import_obj(path, name):
    """Import an OBJ (Blender's C++ importer, Y-up files become Z-up) as one mesh object."""
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path)
    new = [o for o in bpy.data.objects if o not in before]
    if len(new) != 1:
        raise RuntimeError("expected one object from %s, got %d" % (path, len(new)))
    obj = new[0]
    obj.name = name
    activate(obj)
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
SPOT_HEAD = Vector((-math.sin(math.radians(120)), math.cos(math.radians(120)), 0.0))  # where Spot looks


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


def normalize(obj, size=2.0):
    """Bake a transform into the mesh: largest dimension = size, centred in x/y, resting on z=0."""
    mesh = obj.data
    coords = [v.co.copy() for v in mesh.vertices]
    lo = Vector(tuple(min(c[i] for c in coords) for i in range(3)))
    hi = Vector(tuple(max(c[i] for c in coords) for i in range(3)))
    scale = size / max(hi - lo)
    offset = Vector(((lo.x + hi.x) / 2, (lo.y + hi.y) / 2, lo.z))
    mesh.transform(Matrix.Scale(scale, 4) @ Matrix.Translation(-offset))
    obj.location = (0, 0, 0)
    obj.rotation_euler = (0, 0, 0)
    obj.scale = (1, 1, 1)
    mesh.update()
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
    """A copy with its own mesh (and no stylization settings or captures)."""
    copy = obj.copy()
    copy.data = obj.data.copy()
    copy.name = copy.data.name = name
    _link(copy)
    copy.gauss_stylization.styles.clear()
    for key in [k for k in copy.data.keys() if k.startswith("_gauss")]:
        del copy.data[key]
    return copy


def vertex_group(obj, name, predicate):
    """Add a vertex group with weight 1 on the vertices whose (object-space) co passes ``predicate``."""
    group = obj.vertex_groups.new(name=name)
    members = [v.index for v in obj.data.vertices if predicate(v.co)]
    group.add(members, 1.0, 'REPLACE')
    return members


def bounds(obj):
    coords = [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    lo = Vector(tuple(min(c[i] for c in coords) for i in range(3)))
    hi = Vector(tuple(max(c[i] for c in coords) for i in range(3)))
    return lo, hi


# -- stylization -------------------------------------------------------------------------

def stylize(obj, styles, lam=4.0, iterations=100, pin_group="", uncovered='FIRST_SLOT', admm=1):
    """Stylize ``obj`` through the add-on's operator.

    ``styles``: list of dicts with keys of a style slot (preset, sigma, mu, vertex_group,
    orientation, axis_contribution, name). Returns seconds spent in the operator.
    """
    settings = obj.gauss_stylization
    settings.styles.clear()
    for spec in styles:
        slot = settings.styles.add()
        slot.name = spec.get("name", spec.get("preset", "Style").title())
        for key, value in spec.items():
            if key == "orientation":
                slot.orientation = [math.radians(a) for a in value]
            elif key != "name":
                setattr(slot, key, value)
    settings.lam = lam
    settings.admm_iterations = admm
    settings.iterations = iterations
    settings.pin_group = pin_group
    settings.uncovered = uncovered
    activate(obj)
    start = time.perf_counter()
    result = bpy.ops.object.gauss_stylize(iterations=iterations)
    seconds = time.perf_counter() - start
    if result != {'FINISHED'}:
        raise RuntimeError("gauss_stylize on %s returned %s" % (obj.name, result))
    print("  stylized %-22s %6d vertices, %4d steps, lambda %g: %.2f s"
          % (obj.name, len(obj.data.vertices), iterations, lam, seconds))
    return seconds


# -- layout and labels -------------------------------------------------------------------

def material(rgba):
    """A material whose viewport colour Workbench shows (one per distinct colour)."""
    name = "Gauss demo %.2f %.2f %.2f" % tuple(rgba[:3])
    mat = bpy.data.materials.get(name)
    if mat is None:
        mat = bpy.data.materials.new(name)
        mat.diffuse_color = rgba
        mat.roughness = 0.6
    return mat


def color(obj, rgba):
    """Give ``obj`` one colour (replaces its materials)."""
    obj.data.materials.clear()
    obj.data.materials.append(material(rgba))
    if obj.type == 'MESH':
        obj.data.polygons.foreach_set("material_index", [0] * len(obj.data.polygons))
    return obj


def paint_region(obj, vertex_indices, rgba):
    """Colour the faces whose vertices all lie in ``vertex_indices`` (shows a group or pins)."""
    members = set(vertex_indices)
    obj.data.materials.append(material(rgba))
    slot = len(obj.data.materials) - 1
    for polygon in obj.data.polygons:
        if all(v in members for v in polygon.vertices):
            polygon.material_index = slot
    return obj


def place_grid(objects, columns, spacing_x=2.6, spacing_z=3.0):
    """Lay objects out left to right, rows top to bottom, in the x-z plane facing -y."""
    rows = (len(objects) + columns - 1) // columns
    for index, obj in enumerate(objects):
        row, column = divmod(index, columns)
        in_row = min(columns, len(objects) - row * columns)
        obj.location.x = (column - (in_row - 1) / 2) * spacing_x
        obj.location.z = (rows - 1 - row) * spacing_z


def label(obj, text, size=0.24, below=0.45):
    """A caption under ``obj`` (``\n`` for a second line), upright and facing the camera."""
    bpy.context.view_layer.update()
    lo, hi = bounds(obj)
    curve = bpy.data.curves.new(name="Label " + text, type='FONT')
    curve.body = text
    curve.size = size
    curve.align_x = 'CENTER'
    curve.align_y = 'TOP'
    caption = _link(bpy.data.objects.new("Label " + text, curve))
    caption.location = ((lo.x + hi.x) / 2, lo.y, lo.z - below + size)
    caption.rotation_euler = (math.radians(90), 0, 0)
    color(caption, LABEL_COLOR)
    return caption


def ground(size=40.0, z=0.0):
    """A large grey floor (pins scene: shows the feet resting on it)."""
    bpy.ops.mesh.primitive_plane_add(size=size, location=(0, 0, z))
    plane = bpy.context.active_object
    plane.name = "Ground"
    color(plane, (0.80, 0.80, 0.82, 1.0))
    return plane


# -- camera, light, render ---------------------------------------------------------------

def frame_camera(direction=(0.2, -1.0, 0.25), margin=1.08, ignore=()):
    """Orthographic camera looking along -direction, fitted to every visible object."""
    bpy.context.view_layer.update()
    corners = []
    for obj in bpy.context.scene.objects:
        if obj.type in {'MESH', 'FONT'} and obj.name not in ignore:
            corners += [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    center = sum(corners, Vector()) / len(corners)
    view = Vector(direction).normalized()
    rotation = (-view).to_track_quat('-Z', 'Y')
    right, up = rotation @ Vector((1, 0, 0)), rotation @ Vector((0, 1, 0))
    xs = [(c - center).dot(right) for c in corners]
    ys = [(c - center).dot(up) for c in corners]
    aspect = RESOLUTION[0] / RESOLUTION[1]
    width = max(max(xs) - min(xs), (max(ys) - min(ys)) * aspect) * margin
    target = center + right * (max(xs) + min(xs)) / 2 + up * (max(ys) + min(ys)) / 2
    radius = max((c - center).length for c in corners)

    camera_data = bpy.data.cameras.new("Camera")
    camera_data.type = 'ORTHO'
    camera_data.ortho_scale = width
    camera_data.clip_start = 0.01
    camera_data.clip_end = 8 * radius + 10
    camera = _link(bpy.data.objects.new("Camera", camera_data))
    camera.location = target + view * (4 * radius + 5)
    camera.rotation_euler = rotation.to_euler()
    bpy.context.scene.camera = camera
    return camera


def add_sun():
    """A sun for anyone switching the saved .blend to EEVEE/Cycles (Workbench uses studio light)."""
    light_data = bpy.data.lights.new("Sun", type='SUN')
    light_data.energy = 3.0
    sun = _link(bpy.data.objects.new("Sun", light_data))
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    return sun


def setup_render():
    scene = bpy.context.scene
    scene.render.engine = 'BLENDER_WORKBENCH'
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.dither_intensity = 0.0  # no noise: flat areas compress well (gallery PNGs < 100 KB)
    scene.render.image_settings.file_format = 'PNG'
    scene.render.image_settings.color_mode = 'RGB'
    scene.render.image_settings.color_depth = '8'
    scene.render.image_settings.compression = 100
    scene.display.render_aa = '8'
    shading = scene.display.shading
    shading.light = 'STUDIO'
    shading.color_type = 'MATERIAL'
    shading.show_specular_highlight = False
    shading.show_cavity = False
    shading.show_shadows = False
    shading.show_object_outline = False
    scene.view_settings.view_transform = 'Standard'
    scene.view_settings.look = 'None'
    if scene.world is None:
        scene.world = bpy.data.worlds.new("World")
    scene.world.color = BACKGROUND


def finish(name, out_dir, camera_direction=(0.2, -1.0, 0.25), shadows=False):
    """Camera, light, render settings; write OUT_DIR/NAME.png and OUT_DIR/NAME.blend."""
    os.makedirs(out_dir, exist_ok=True)
    if bpy.context.scene.camera is None:
        frame_camera(camera_direction)
    add_sun()
    setup_render()
    if shadows:  # a soft shadow straight down: shows whether a shape touches the floor
        bpy.context.scene.display.shading.show_shadows = True
        bpy.context.scene.display.shading.shadow_intensity = 0.5
        bpy.context.scene.display.light_direction = (0.15, 0.25, 0.95)
    png = os.path.join(out_dir, name + ".png")
    blend = os.path.join(out_dir, name + ".blend")
    bpy.context.scene.render.filepath = png
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print("  rendered %s (%.2f s)" % (png, time.perf_counter() - start))
    bpy.ops.wm.save_as_mainfile(filepath=blend, check_existing=False, compress=True)
    if os.path.exists(blend + "1"):  # the backup Blender makes of the previous run's file
        os.remove(blend + "1")
    print("  saved %s" % blend)
    return png, blend


def run(module_globals):
    """Entry point of a scene script run directly: ``-- BUILD_DIR OUT_DIR``."""
    name = module_globals["NAME"]
    build_dir, out_dir = parse_build_out(
        script_args(), "blender -b --factory-startup -P blender_scenes/%s.py -- BUILD_DIR OUT_DIR" % name)
    load_addon(build_dir)
    reset_scene()
    start = time.perf_counter()
    module_globals["build"]()
    finish(name, out_dir, **module_globals.get("FINISH", {}))
    print("== %s: %.1f s" % (name, time.perf_counter() - start))
