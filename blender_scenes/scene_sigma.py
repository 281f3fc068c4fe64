"""Sigma, the sharpness of the preference function (paper Sections 3.1 and 4.2): with a
low sigma the bumps of neighbouring preferred normals merge and the shape barely takes the
style; a high sigma pulls each face firmly to its nearest preferred normal, giving crisper,
more jagged facets. Same mesh, Dodecahedron style, lambda 8, 200 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "sigma"
SIGMAS = (1.0, 4.0, 20.0)
LAMBDA, STEPS = 8.0, 200


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.sweep(source, [("sigma %g" % sigma, [dict(preset='DODECAHEDRON', sigma=sigma)],
                               dict(lam=LAMBDA, iterations=STEPS)) for sigma in SIGMAS],
                     columns=2, spacing_x=2.7, spacing_z=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
