"""Sigma, the sharpness of the preference function (paper Sections 3.1 and 4.2): with a
low sigma the bumps of neighbouring preferred normals merge and the shape barely takes the
style; a high sigma pulls each face firmly to its nearest preferred normal, giving crisper,
more jagged facets. Same mesh, Dodecahedron style, lambda 8, 200 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "sigma"
SIGMAS = (1.0, 4.0, 20.0)
LAMBDA, STEPS = 8.0, 200


def build():
    source, _ = common.demo_mesh(common.SPOT, "Original")
    common.color(source, common.ORIGINAL_COLOR)
    objects, labels = [source], ["Original"]
    for sigma in SIGMAS:
        obj = common.color(common.duplicate(source, "Sigma %g" % sigma), common.STYLIZED_COLOR)
        common.stylize(obj, [dict(name="Dodecahedron", preset='DODECAHEDRON', sigma=sigma)],
                       lam=LAMBDA, iterations=STEPS)
        objects.append(obj)
        labels.append("sigma %g" % sigma)
    common.place_grid(objects, columns=2, spacing_x=2.7, spacing_z=2.7)
    for obj, text in zip(objects, labels):
        common.label(obj, text)


if __name__ == "__main__":
    common.run(globals())
