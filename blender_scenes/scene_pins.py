"""Pins (positional constraints, paper Section 5.1 and Fig. 13): the vertices of the
vertex group "Feet" (red) keep their place, so the stylized shape still stands on the
ground; without pins the shape shrinks and floats. Tetrahedron style, lambda 8, 200 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "pins"
LAMBDA, STEPS = 8.0, 200
FEET_HEIGHT = 0.12  # vertices below this height (the shape is 2 units long) are pinned
FINISH = dict(camera_direction=(0.15, -1.0, 0.12))


def build():
    import bpy
    source, _ = common.demo_mesh(common.SPOT, "Original")
    common.color(source, common.ORIGINAL_COLOR)
    feet = common.vertex_group(source, "Feet", lambda co: co.z < FEET_HEIGHT)
    common.paint_region(source, feet, common.PIN_COLOR)
    free = common.color(common.duplicate(source, "No pins"), common.STYLIZED_COLOR)
    pinned = common.color(common.duplicate(source, "Feet pinned"), common.STYLIZED_COLOR)
    common.paint_region(pinned, feet, common.PIN_COLOR)
    common.stylize(free, [dict(preset='TETRAHEDRON')], lam=LAMBDA, iterations=STEPS)
    common.stylize(pinned, [dict(preset='TETRAHEDRON')], lam=LAMBDA, iterations=STEPS, pin_group="Feet")
    objects = [source, free, pinned]
    for obj in objects:
        lowest = min(v.co.z for v in obj.data.vertices)
        print("  %-12s lowest point %.3f above the ground" % (obj.name, lowest))
    common.place_grid(objects, columns=3, spacing_x=2.7)
    slabs = []
    for obj in objects:  # a thin slab under each shape, its top at the original's ground level
        bpy.ops.mesh.primitive_cube_add(size=1.0, location=(obj.location.x, 0.0, -0.04))
        slab = bpy.context.active_object
        slab.name = "Ground " + obj.name
        slab.scale = (2.3, 1.6, 0.08)
        common.color(slab, (0.45, 0.45, 0.48, 1.0))
        slabs.append(slab)
    for slab, text in zip(slabs, ["Original\npin group in red", "Tetrahedron\nno pins", "Tetrahedron\nfeet pinned"]):
        common.label(slab, text, below=0.25)


if __name__ == "__main__":
    common.run(globals())
