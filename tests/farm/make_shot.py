"""Make an animated shot for the farm tests and measurements: a mesh bent by a two-bone armature over
a frame range, with the add-on's settings on it, saved as a .blend.

    blender -b --factory-startup --python-exit-code 1 -P tests/farm/make_shot.py -- BUILD_DIR OUT.blend
        [--frames 1-48] [--mesh PATH.obj] [--warm-start] [--bake-steps N] [--script-steps N] [--warmup N]

Without --mesh the mesh is a capsule (a stretched 24x16 UV sphere, 370 vertices) named "Capsule"; with
it the .obj is imported (named "Shot"). Either bends by 60 degrees above its middle (scene_kit.bending_rig).
The scene's range is the frames, so Bake Animation and a farm bake read the same range from the file.
"""

import argparse
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "blender_scenes"))
import scene_kit  # noqa: E402


def main(argv):
    parser = argparse.ArgumentParser(prog="make_shot.py")
    parser.add_argument("build")
    parser.add_argument("out")
    parser.add_argument("--frames", default="1-48")
    parser.add_argument("--mesh")
    parser.add_argument("--warm-start", action="store_true")
    parser.add_argument("--bake-steps", type=int, default=5)
    parser.add_argument("--script-steps", type=int, default=30)
    parser.add_argument("--warmup", type=int)
    args = parser.parse_args(argv)
    addon = scene_kit.load_addon(args.build)
    scene_kit.reset_scene()
    first, last = (int(x) for x in args.frames.split("-"))
    if args.mesh:
        obj = scene_kit.import_obj(args.mesh, "Shot")
        scene_kit.normalize(obj, size=4.0)
    else:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=16)
        obj = bpy.context.active_object
        obj.name = "Capsule"
        co = scene_kit.coords(obj)
        co[:, 2] *= 2.0
        addon.mesh_io.write_vertex_coords(obj.data, co)
        obj.data.update()
    co = scene_kit.coords(obj)
    low, high = co[:, 2].min(), co[:, 2].max()
    middle, third = (low + high) / 2.0, (high - low) / 6.0
    weights = np.clip((co[:, 2] - (middle - third)) / (2.0 * third), 0.0, 1.0)
    scene_kit.bending_rig(obj, (0, 0, middle), (0, 0, 1), weights, 60.0, (first, last))
    settings = obj.gauss_stylization
    addon.settings_io.apply_dict(settings, {
        "lam": 2.0, "iterations": args.script_steps, "bake_steps": args.bake_steps,
        "bake_warm_start": args.warm_start, "bake_scene_range": True, "styles": [{"preset": 'CUBE'}]})
    if args.warmup is not None:
        settings.bake_warmup_frames = args.warmup
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.out))
    print("make_shot: %s: '%s' (%d vertices), frames %d-%d" % (args.out, obj.name, len(obj.data.vertices),
                                                                first, last))


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
