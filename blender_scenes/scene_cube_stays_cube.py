"""Sanity check: the Cube style on a mesh that already is an axis-aligned cube changes
nothing (every face normal is already a preferred normal), even at a high lambda. The
label reports the largest vertex displacement measured after stylization."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "cube_stays_cube"
LAMBDA, STEPS = 20.0, 200


def subdivided_cube(name):
    """../shared/meshes/small/cube_gaussstylization_728.obj, or a Blender cube subdivided flat."""
    path = scene_kit.shared_mesh("small/cube_gaussstylization_728.obj")
    if path is not None:
        return scene_kit.import_obj(path, name)
    bpy.ops.mesh.primitive_cube_add()
    obj = bpy.context.active_object
    obj.name = name
    modifier = obj.modifiers.new("Subdivide", 'SUBSURF')
    modifier.subdivision_type = 'SIMPLE'
    modifier.levels = 3
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    return obj


def build():
    original = subdivided_cube("Cube")
    scene_kit.normalize(original)
    scene_kit.set_flat(original)
    render_kit.color(original, render_kit.ORIGINAL_COLOR)
    stylized = render_kit.color(scene_kit.duplicate(original, "Cube Stylized"), render_kit.STYLIZED_COLOR)
    before = scene_kit.coords(stylized)
    scene_kit.stylize(stylized, [dict(preset='CUBE')], lam=LAMBDA, iterations=STEPS)
    moved = float(np.linalg.norm(scene_kit.coords(stylized) - before, axis=1).max())
    print("  largest vertex move: %.3g (cube edge length 2)" % moved)
    if moved > 1e-4:
        raise RuntimeError("the cube style moved a cube's vertices by %g" % moved)
    render_kit.show_grid([original, stylized],
                         ["Cube mesh\n%d vertices" % len(original.data.vertices),
                          "Cube style, lambda %g\nlargest move %.0e" % (LAMBDA, max(moved, 1e-16))],
                         columns=2, spacing_x=3.0)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
