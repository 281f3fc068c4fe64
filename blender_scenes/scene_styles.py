"""One mesh, seven styles side by side. The preferred normals need not be a cube's or
point-symmetric (tetrahedron, dodecahedron, hexagonal prism) nor a discrete set (cylinder,
cone, double cone prefer rings of normals on the Gauss sphere). Paper: Sections 3.1, 5.2,
Fig. 3 and 16."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "styles"
PRESETS = ("CUBE", "TETRAHEDRON", "DODECAHEDRON", "HEXAGONAL_PRISM", "CYLINDER", "CONE", "DOUBLE_CONE")
LAMBDA, STEPS = 8.0, 200


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.sweep(source, [(preset.replace("_", " ").capitalize(), [dict(preset=preset)],
                               dict(lam=LAMBDA, iterations=STEPS)) for preset in PRESETS],
                     columns=4, spacing_x=2.6, spacing_z=2.9)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
