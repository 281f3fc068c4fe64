"""Sanity check: the Cube style on a mesh that already is an axis-aligned cube changes
nothing (every face normal is already a preferred normal), even at a high lambda. The
label reports the largest vertex displacement measured after stylization."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "cube_stays_cube"


def subdivided_cube(name):
    """../shared/meshes/small/cube_gaussstylization_728.obj, or a Blender cube subdivided flat."""
    path = common.shared_mesh("small/cube_gaussstylization_728.obj")
    if path is not None:
        return common.import_obj(path, name)
    import bpy
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
    common.normalize(original)
    common.set_flat(original)
    common.color(original, common.ORIGINAL_COLOR)
    stylized = common.color(common.duplicate(original, "Cube Stylized"), common.STYLIZED_COLOR)
    before = [v.co.copy() for v in stylized.data.vertices]
    common.stylize(stylized, [dict(preset='CUBE')], lam=20.0, iterations=200)
    moved = max((v.co - b).length for v, b in zip(stylized.data.vertices, before))
    print("  largest vertex move: %.3g (cube edge length 2)" % moved)
    if moved > 1e-4:
        raise RuntimeError("the cube style moved a cube's vertices by %g" % moved)
    common.place_grid([original, stylized], columns=2, spacing_x=3.0)
    common.label(original, "Cube mesh\n%d vertices" % len(original.data.vertices))
    common.label(stylized, "Cube style, lambda 20\nlargest move %.0e" % max(moved, 1e-16))


if __name__ == "__main__":
    common.run(globals())
