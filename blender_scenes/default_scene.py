"""The main job's scene (scripts/run_main.sh): a subdivided Suzanne stylized with the default
preset at the add-on's default settings, next to the original. Needs no test meshes.

    blender -b --factory-startup --python-exit-code 1 -P blender_scenes/default_scene.py -- BUILD_DIR OUT_DIR

writes OUT_DIR/default_scene.blend and OUT_DIR/default_scene.png.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "default_scene"
STEPS = 100


def build():
    original = scene_kit.suzanne("Suzanne", subdivisions=2)
    scene_kit.normalize(original)
    scene_kit.set_flat(original)
    render_kit.color(original, render_kit.ORIGINAL_COLOR)
    stylized = render_kit.color(scene_kit.duplicate(original, "Suzanne Stylized"), render_kit.STYLIZED_COLOR)
    # No settings given: one slot of the default preset, everything else at the add-on's defaults.
    scene_kit.stylize(stylized, [{}], iterations=STEPS)
    settings = stylized.gauss_stylization
    render_kit.show_grid(
        [original, stylized],
        ["Original\n%d vertices" % len(original.data.vertices),
         "%s style\nlambda %g, %d steps" % (settings.styles[0].name, settings.lam, STEPS)],
        columns=2, spacing_x=2.8)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
