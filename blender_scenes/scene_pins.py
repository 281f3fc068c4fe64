"""Pins (positional constraints, paper Section 5.1 and Fig. 13): the vertices of the
vertex group "Feet" (red) keep their place, so the stylized shape still stands on the
ground; without pins the shape shrinks and floats. Tetrahedron style, lambda 8, 200 steps."""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "pins"
LAMBDA, STEPS = 8.0, 200
FEET_HEIGHT = 0.12  # vertices below this height (the shape is 2 units long) are pinned
FINISH = dict(camera_direction=(0.15, -1.0, 0.12))


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.color(source, render_kit.ORIGINAL_COLOR)
    feet = scene_kit.vertex_group(source, "Feet", lambda co: co[:, 2] < FEET_HEIGHT)
    render_kit.paint_region(source, feet, render_kit.PIN_COLOR)
    free = render_kit.color(scene_kit.duplicate(source, "No pins"), render_kit.STYLIZED_COLOR)
    pinned = render_kit.color(scene_kit.duplicate(source, "Feet pinned"), render_kit.STYLIZED_COLOR)
    render_kit.paint_region(pinned, feet, render_kit.PIN_COLOR)
    scene_kit.stylize(free, [dict(preset='TETRAHEDRON')], lam=LAMBDA, iterations=STEPS)
    scene_kit.stylize(pinned, [dict(preset='TETRAHEDRON')], lam=LAMBDA, iterations=STEPS, pin_group="Feet")
    objects = [source, free, pinned]
    for obj in objects:
        print("  %-12s lowest point %.3f above the ground" % (obj.name, scene_kit.coords(obj)[:, 2].min()))
    render_kit.place_grid(objects, columns=3, spacing_x=2.7)
    slabs = []
    for obj in objects:  # a thin slab under each shape, its top at the original's ground level
        bpy.ops.mesh.primitive_cube_add(size=1.0, location=(obj.location.x, 0.0, -0.04))
        slab = bpy.context.active_object
        slab.name = "Ground " + obj.name
        slab.scale = (2.3, 1.6, 0.08)
        render_kit.color(slab, (0.45, 0.45, 0.48, 1.0))
        slabs.append(slab)
    for slab, text in zip(slabs, ["Original\npin group in red", "Tetrahedron\nno pins", "Tetrahedron\nfeet pinned"]):
        render_kit.label(slab, text, below=0.25)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
