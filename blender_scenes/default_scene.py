"""The main job's scene (scripts/run_main.sh): a subdivided Suzanne stylized with the Cube
preset at the add-on's default settings, next to the original. Needs no test meshes.

    blender -b --factory-startup --python-exit-code 1 -P blender_scenes/default_scene.py -- BUILD_DIR OUT_DIR

writes OUT_DIR/default_scene.blend and OUT_DIR/default_scene.png.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "default_scene"


def build():
    original = common.suzanne("Suzanne", subdivisions=2)
    common.normalize(original)
    common.set_flat(original)
    common.color(original, common.ORIGINAL_COLOR)
    stylized = common.color(common.duplicate(original, "Suzanne Cube"), common.STYLIZED_COLOR)
    # The add-on's defaults: Cube, sigma 4, mu 1, lambda 4, 1 ADMM iteration, 100 steps.
    common.stylize(stylized, [dict(name="Cube", preset='CUBE')], lam=4.0, iterations=100)
    common.place_grid([original, stylized], columns=2, spacing_x=2.8)
    common.label(original, "Original\n%d vertices" % len(original.data.vertices))
    common.label(stylized, "Cube style\nlambda 4, 100 steps")


if __name__ == "__main__":
    common.run(globals())
