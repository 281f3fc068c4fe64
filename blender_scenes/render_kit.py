"""Showing a demo scene: colours, layout, labels, camera, light, Workbench render settings,
saving, and the entry point of a scene script.

Every scene module defines ``NAME`` (output file stem) and ``build()`` (fills the empty
scene), optionally ``FINISH`` (keywords of finish()). A scene can run on its own:

    blender -b --factory-startup --python-exit-code 1 -P blender_scenes/scene_styles.py -- BUILD_DIR OUT_DIR

or all together through ``render_all.py``. Works with Blender 3.4 and 4.x (Workbench
render engine only, no bgl, no EEVEE/Cycles specifics).
"""

import math
import os
import sys
import time

import bpy
from mathutils import Vector

import scene_kit

RESOLUTION = (480, 360)
BACKGROUND = (0.93, 0.93, 0.95)
ORIGINAL_COLOR = (0.62, 0.64, 0.68, 1.0)   # grey: the unchanged input
STYLIZED_COLOR = (0.86, 0.55, 0.30, 1.0)   # warm: the stylized result
SECOND_COLOR = (0.33, 0.56, 0.82, 1.0)     # blue: a second style region
PIN_COLOR = (0.85, 0.20, 0.20, 1.0)
LABEL_COLOR = (0.12, 0.12, 0.14, 1.0)


# -- colours -----------------------------------------------------------------------------

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


# -- layout and labels -------------------------------------------------------------------

def bounds(obj):
    coords = [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    lo = Vector(tuple(min(c[i] for c in coords) for i in range(3)))
    hi = Vector(tuple(max(c[i] for c in coords) for i in range(3)))
    return lo, hi


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
    caption = scene_kit.link(bpy.data.objects.new("Label " + text, curve))
    caption.location = ((lo.x + hi.x) / 2, lo.y, lo.z - below + size)
    caption.rotation_euler = (math.radians(90), 0, 0)
    color(caption, LABEL_COLOR)
    return caption


def show_grid(objects, labels, columns, spacing_x=2.6, spacing_z=3.0):
    """place_grid() the objects and put each one's label under it."""
    place_grid(objects, columns, spacing_x, spacing_z)
    for obj, text in zip(objects, labels):
        label(obj, text)


def sweep(source, variants, columns, spacing_x=2.6, spacing_z=3.0):
    """The grey ``source`` ("Original") and one stylized copy per variant, in a labelled grid.

    variants: (label, slot specs, object settings) per copy, as scene_kit.stylize() takes them;
    the copy is named after the label's first line."""
    color(source, ORIGINAL_COLOR)
    objects, labels = [source], ["Original"]
    for text, styles, settings in variants:
        copy = color(scene_kit.duplicate(source, text.split("\n")[0]), STYLIZED_COLOR)
        scene_kit.stylize(copy, styles, **settings)
        objects.append(copy)
        labels.append(text)
    show_grid(objects, labels, columns, spacing_x, spacing_z)
    return objects


# -- camera, light, render ---------------------------------------------------------------

def frame_camera(direction=(0.2, -1.0, 0.25), margin=1.08):
    """Orthographic camera looking along -direction, fitted to every visible object."""
    bpy.context.view_layer.update()
    corners = []
    for obj in bpy.context.scene.objects:
        if obj.type in {'MESH', 'FONT'}:
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
    camera = scene_kit.link(bpy.data.objects.new("Camera", camera_data))
    camera.location = target + view * (4 * radius + 5)
    camera.rotation_euler = rotation.to_euler()
    bpy.context.scene.camera = camera
    return camera


def add_sun():
    """A sun for anyone switching the saved .blend to EEVEE/Cycles (Workbench uses studio light)."""
    light_data = bpy.data.lights.new("Sun", type='SUN')
    light_data.energy = 3.0
    sun = scene_kit.link(bpy.data.objects.new("Sun", light_data))
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


# -- entry point -------------------------------------------------------------------------

def script_args():
    """Arguments after ``--`` on Blender's command line."""
    argv = sys.argv
    return argv[argv.index("--") + 1:] if "--" in argv else []


_out_dir = None


def output_folder():
    """The folder the scene being built is saved to (for files it writes next to its .blend)."""
    return _out_dir


def render_scene(scene, out_dir):
    """Build ``scene`` (a scene module) in an empty scene, render and save it. Returns the PNG path."""
    global _out_dir
    _out_dir = out_dir
    os.makedirs(out_dir, exist_ok=True)
    start = time.perf_counter()
    print("== %s" % scene.NAME)
    scene_kit.reset_scene()
    scene.build()
    png, _ = finish(scene.NAME, out_dir, **getattr(scene, "FINISH", {}))
    print("== %s: %.1f s" % (scene.NAME, time.perf_counter() - start))
    return png


def run(scene):
    """Entry point of a scene script run directly: ``-- BUILD_DIR OUT_DIR``."""
    args = script_args()
    if len(args) < 2:
        raise SystemExit("usage: blender -b --factory-startup -P blender_scenes/%s.py -- BUILD_DIR OUT_DIR"
                         % scene.NAME)
    scene_kit.load_addon(os.path.abspath(args[0]))
    render_scene(scene, os.path.abspath(args[1]))
