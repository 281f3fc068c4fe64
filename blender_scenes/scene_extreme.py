"""'Extreme' cubification (paper Section 5.2, Fig. 16 left): as lambda grows the faces get
almost exactly the cube's normals and only a pictogram of the shape remains. Cube style,
default sigma, 300 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "extreme_lambda"
LAMBDAS = (4.0, 20.0, 100.0)
STEPS = 300


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.BUNNY, "Original")
    render_kit.sweep(source, [("lambda %g" % lam, [dict(preset='CUBE')], dict(lam=lam, iterations=STEPS))
                              for lam in LAMBDAS],
                     columns=2, spacing_x=2.7, spacing_z=2.6)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
