"""Style Reach: every face coloured by its angle to the normal its style prefers (green: reached,
yellow: 15 degrees, red: 30 or more), the add-on's face attribute 'gauss_style_angle' (Store Style
Angles) rendered through one material per step of the overlay's colour scale. Spot with the Cube style
before it runs, after 10 steps and after 200 (lambda 4)."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "style_reach"
STEPS = (0, 10, 200)
BANDS = 12  # materials along the scale


def show_angles(obj):
    """Store Style Angles, then each face the material of its band of the scale. Returns the mean angle."""
    addon = scene_kit.addon
    scene_kit.activate(obj)
    assert bpy.ops.object.gauss_store_style_angles() == {'FINISHED'}
    angles = np.empty(len(obj.data.polygons), np.float32)
    obj.data.attributes[addon.reach_operators.ATTRIBUTE].data.foreach_get("value", angles)
    top = addon.sphere.style_reach.SCALE_DEGREES
    centres = (np.arange(BANDS) + 0.5) * top / BANDS
    obj.data.materials.clear()
    for rgba in addon.sphere.style_reach.colours(np.append(centres, np.nan)):  # the last: unstyled, grey
        obj.data.materials.append(render_kit.material(tuple(float(c) for c in rgba)))
    band = np.clip((angles / top * BANDS).astype(np.int64), 0, BANDS - 1)
    band[angles < 0] = BANDS  # Store Style Angles' value where no style acts
    obj.data.polygons.foreach_set("material_index", band.astype(np.int32))
    return float(angles[angles >= 0].mean())


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    objects, labels = [], []
    for steps in STEPS:
        copy = scene_kit.duplicate(source, "Cube %d steps" % steps)
        if steps:
            scene_kit.stylize(copy, [dict(preset='CUBE')], iterations=steps)
        else:
            scene_kit.addon.settings_io.add_slot(copy.gauss_stylization, {"preset": 'CUBE'})
        mean = show_angles(copy)
        print("  %-16s mean angle %.1f degrees" % (copy.name, mean))
        objects.append(copy)
        labels.append("%s\nmean %.1f degrees" % ("Cube style, before" if not steps else "%d steps" % steps, mean))
    source.hide_render = True
    render_kit.show_grid(objects, labels, columns=3, spacing_x=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
