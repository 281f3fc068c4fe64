"""One mesh, seven styles side by side. The preferred normals need not be a cube's or
point-symmetric (tetrahedron, dodecahedron, hexagonal prism) nor a discrete set (cylinder,
cone, double cone prefer rings of normals on the Gauss sphere). Paper: Sections 3.1, 5.2,
Fig. 3 and 16."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "styles"
STYLES = [
    ("CUBE", "Cube"), ("TETRAHEDRON", "Tetrahedron"), ("DODECAHEDRON", "Dodecahedron"),
    ("HEXAGONAL_PRISM", "Hexagonal prism"), ("CYLINDER", "Cylinder"), ("CONE", "Cone"),
    ("DOUBLE_CONE", "Double cone"),
]
LAMBDA, STEPS = 8.0, 200


def build():
    source, _ = common.demo_mesh(common.SPOT, "Original")
    common.color(source, common.ORIGINAL_COLOR)
    objects, labels = [source], ["Original"]
    for preset, title in STYLES:
        obj = common.color(common.duplicate(source, title), common.STYLIZED_COLOR)
        common.stylize(obj, [dict(name=title, preset=preset, sigma=4.0)], lam=LAMBDA, iterations=STEPS)
        objects.append(obj)
        labels.append(title)
    common.place_grid(objects, columns=4, spacing_x=2.6, spacing_z=2.9)
    for obj, text in zip(objects, labels):
        common.label(obj, text)


if __name__ == "__main__":
    common.run(globals())
