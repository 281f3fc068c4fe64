"""The Gauss sphere (paper Section 5.2, Fig. 15): what the viewport overlay shows
(Show Gauss Sphere), drawn into the scene as geometry, because the overlay is a viewport
drawing that a render does not see. Each shape stands beside a sphere of directions
coloured by g of its style (dark: unwanted, pale yellow: preferred), the style's
preferred normals as white dots and the shape's face normals as cyan points (the same
area-weighted sample the overlay draws). Stylized, the normals gather at the preferred
directions. The sphere is in the shape's own frame and seen from the same camera."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "gauss_sphere"
LAMBDA, STEPS = 8.0, 200
RADIUS = 0.95
BINS = 32                 # heat-map colours (one material each)
POINT, DOT = 0.022, 0.08  # disc radii of a face normal and a preferred normal, times RADIUS
FINISH = dict(camera_direction=(0.0, -1.0, 0.35))


def discs(centres, normals, radius, sides=8):
    """Vertices and faces of flat discs (one polygon each) at ``centres`` facing ``normals``."""
    vertices, faces = [], []
    angles = np.linspace(0.0, 2.0 * np.pi, sides, endpoint=False)
    for centre, normal in zip(centres, normals):
        side = np.cross(normal, [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0])
        side /= np.linalg.norm(side)
        other = np.cross(normal, side)
        start = len(vertices)
        vertices += list(centre + radius * (np.outer(np.cos(angles), side) + np.outer(np.sin(angles), other)))
        faces.append(tuple(range(start, start + sides)))
    return vertices, faces


def mesh_object(name, vertices, faces):
    """A mesh object; its vertices lifted by RADIUS, so a sphere centred at 0 rests on the floor."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(x, y, z + RADIUS) for x, y, z in vertices], [], faces)
    mesh.update()
    return scene_kit.link(bpy.data.objects.new(name, mesh))


def gauss_sphere_of(obj):
    """The sphere of ``obj`` (its active style and its face normals now), as one object."""
    addon = scene_kit.addon
    slot = addon.styles.active_slot(obj.gauss_stylization)
    style = addon.styles.checked_style(addon.native.core(), obj, slot)
    unit, triangles = addon.sphere.gauss_sphere.icosphere()
    sphere = mesh_object("Gauss sphere of " + obj.name, unit * RADIUS, [tuple(t) for t in triangles])
    # Faces coloured by the mean g of their corners, in BINS steps of the overlay's heat map.
    g = np.asarray(style.value(unit))[triangles].mean(axis=1)
    level = np.clip((g * BINS).astype(int), 0, BINS - 1)
    colours = addon.sphere.gauss_sphere.heat_colours((np.arange(BINS) + 0.5) / BINS)
    for rgba in colours:
        sphere.data.materials.append(render_kit.material(tuple(rgba)))
    sphere.data.polygons.foreach_set("material_index", level.tolist())

    preferred = np.asarray(style.normals)
    normals = addon.sphere.sphere_overlay.face_normal_sample(obj)
    point_colour = tuple(addon.sphere.sphere_overlay.NORMAL_POINTS[:3]) + (1.0,)  # the overlay's
    parts = [(normals * RADIUS * 1.003, normals, POINT * RADIUS, point_colour),
             (preferred * RADIUS * 1.004, preferred, DOT * RADIUS * 1.3, (0.0, 0.0, 0.0, 1.0)),
             (preferred * RADIUS * 1.006, preferred, DOT * RADIUS, (1.0, 1.0, 1.0, 1.0))]
    for centres, facing, radius, rgba in parts:
        marks = mesh_object(sphere.name + " marks", *discs(centres, facing, radius))
        render_kit.color(marks, rgba)
        marks.parent = sphere
    scene_kit.set_flat(sphere, False)
    return sphere


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.color(source, render_kit.ORIGINAL_COLOR)
    scene_kit.addon.settings_io.apply_dict(source.gauss_stylization, {"styles": [{"preset": 'CUBE'}]})
    styled = render_kit.color(scene_kit.duplicate(source, "Cube style"), render_kit.STYLIZED_COLOR)
    scene_kit.stylize(styled, [dict(preset='CUBE')], lam=LAMBDA, iterations=STEPS)
    spheres = [gauss_sphere_of(source), gauss_sphere_of(styled)]
    render_kit.show_grid([source, spheres[0], styled, spheres[1]],
                         ["Original", "its Gauss sphere\n(Cube style's g)",
                          "Cube style, lambda %g" % LAMBDA, "its Gauss sphere:\nnormals gathered"],
                         columns=2, spacing_x=2.6, spacing_z=2.9)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
