"""Sheet Metal: no preferred directions; each face turns towards the one bending direction of its
neighbourhood, so the surface unbends into pieces that bend one way at a time, like rolled or folded
sheet (docs/styles.md#sheet-metal). Spot, Sheet Metal at its own Sigma, at half, once and twice the
Lambda the add-on names for it (schema.LOOK_LAMBDA), 200 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "sheet_metal"
SCALES = (0.5, 1.0, 2.0)
STEPS = 200


def build():
    look = scene_kit.addon.settings.schema.LOOK_LAMBDA["sheet_metal"]
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.sweep(source, [("Sheet Metal\nlambda %g" % (scale * look), [dict(preset='SHEET_METAL')],
                               dict(lam=scale * look, iterations=STEPS)) for scale in SCALES],
                     columns=2, spacing_x=2.7, spacing_z=2.9)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
