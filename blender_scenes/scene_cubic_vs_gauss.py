"""Cubic vs Gauss: one mesh stylized by the two methods the add-on offers. Cubic Stylization (Liu &
Jacobson 2019) at its reference's default lambda 0.2, run until it has settled, beside this paper's
Gauss method with the Cube style at its defaults. Both prefer the axis directions; the cubic method
turns whole regions around each vertex (a rotation per vertex), the Gauss method turns each face."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "cubic_vs_gauss"
STEPS = 200  # Spot settles within ~110 steps with either method


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.sweep(source, [("Cubic\nlambda 0.2", [dict(preset='CUBE')], dict(method='CUBIC', cubic_lambda=0.2,
                                                                            iterations=STEPS)),
                              ("Gauss, Cube style\nlambda 4", [dict(preset='CUBE')], dict(method='GAUSS', lam=4.0,
                                                                                        iterations=STEPS))],
                     columns=3, spacing_x=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
