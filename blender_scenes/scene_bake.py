"""Animation bake: a capsule bent by a two-bone armature over ten frames, baked with
Bake Animation (warm start: every frame continues from the previous frame's result, so the style
holds still while the shape moves) into a point cache that a Mesh Cache modifier plays. Top row:
the animation at frames 1, 4, 7 and 10; bottom row: the same frames of the baked cache. Cube style,
lambda 2, Keep Volume, Script Steps 60 for the first frame, Bake Steps 5 for each later one."""

import math
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "bake"
FRAMES = (1, 10)
SHOWN = (1, 4, 7, 10)
BEND_DEGREES = 90.0  # bent over to lie along another axis, where the Cube style lets it be
LAMBDA, FIRST_STEPS, BAKE_STEPS = 2.0, 60, 5
FINISH = dict(camera_direction=(0.35, -1.0, 0.2))


def _capsule():
    """A UV sphere stretched to a capsule 3 units tall, standing on its lower end at the origin."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.5)
    obj = bpy.context.active_object
    obj.name = "Capsule"
    co = scene_kit.coords(obj)
    co[:, 2] = co[:, 2] * 3.0 + 1.5
    scene_kit.addon.mesh_io.write_vertex_coords(obj.data, co)
    obj.data.update()
    scene_kit.set_flat(obj)
    return obj


def build():
    obj = _capsule()
    co = scene_kit.coords(obj)
    bent = np.clip((co[:, 2] - 1.2) / 0.6, 0.0, 1.0)  # the upper half, blended over 0.6 units
    rig = scene_kit.bending_rig(obj, (0, 0, 1.5), (0, 0, 1), bent, BEND_DEGREES, FRAMES)
    scene_kit.addon.settings_io.apply_dict(obj.gauss_stylization, dict(
        styles=[dict(preset='CUBE')], lam=LAMBDA, iterations=FIRST_STEPS, bake_steps=BAKE_STEPS, keep_volume=True))
    scene_kit.activate(obj)
    cache = os.path.join(render_kit.output_folder(), NAME + "_capsule.pc2")
    result = bpy.ops.object.gauss_bake_animation(frame_start=FRAMES[0], frame_end=FRAMES[1],
                                                 filepath=cache, warm_start=True)
    assert result == {'FINISHED'}, result
    modifier = scene_kit.addon.mesh.cache_modifier.find(obj)
    rows = {True: [], False: []}
    for baked in (False, True):
        modifier.show_viewport = modifier.show_render = baked
        for frame in SHOWN:
            bpy.context.scene.frame_set(frame)
            shot = scene_kit.snapshot(obj, "%s frame %d" % ("Baked" if baked else "Animation", frame))
            render_kit.color(shot, render_kit.STYLIZED_COLOR if baked else render_kit.ORIGINAL_COLOR)
            shot.rotation_euler.z = math.radians(90)  # the bend (about the bone's X axis) across the view
            rows[baked].append(shot)
    obj.hide_render = obj.hide_viewport = rig.hide_render = rig.hide_viewport = True
    bpy.context.scene.frame_set(FRAMES[0])
    shots = rows[False] + rows[True]
    labels = ["frame %d" % frame for frame in SHOWN] + ["baked frame %d" % frame for frame in SHOWN]
    render_kit.show_grid(shots, labels, columns=len(SHOWN), spacing_x=2.6, spacing_z=3.9)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
