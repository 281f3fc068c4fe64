"""'Extreme' cubification (paper Section 5.2, Fig. 16 left): as lambda grows the faces get
almost exactly the cube's normals and only a pictogram of the shape remains. Cube style,
sigma 4, 300 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "extreme_lambda"
LAMBDAS = (4.0, 20.0, 100.0)
STEPS = 300


def build():
    source, _ = common.demo_mesh(common.BUNNY, "Original")
    common.color(source, common.ORIGINAL_COLOR)
    objects, labels = [source], ["Original"]
    for lam in LAMBDAS:
        obj = common.color(common.duplicate(source, "Lambda %g" % lam), common.STYLIZED_COLOR)
        common.stylize(obj, [dict(preset='CUBE')], lam=lam, iterations=STEPS)
        objects.append(obj)
        labels.append("lambda %g" % lam)
    common.place_grid(objects, columns=2, spacing_x=2.7, spacing_z=2.6)
    for obj, text in zip(objects, labels):
        common.label(obj, text)


if __name__ == "__main__":
    common.run(globals())
