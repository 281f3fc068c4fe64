"""Two styles on one mesh by vertex groups (paper Section 5.1, Fig. 14): the head
(group "Head", blue) prefers dodecahedron normals, the body (group "Body") cube normals.
Left to right: the regions, all Cube, all Dodecahedron, both. Lambda 8, 200 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

NAME = "multistyle"
LAMBDA, STEPS = 8.0, 200


def build():
    source, is_spot = common.demo_mesh(common.SPOT, "Regions")
    common.color(source, common.STYLIZED_COLOR)
    if is_spot:
        in_head = lambda co: co.xy.dot(common.SPOT_HEAD.xy) > 0.4  # noqa: E731
    else:  # Suzanne: the upper half
        in_head = lambda co: co.z > 0.8  # noqa: E731
    head = common.vertex_group(source, "Head", in_head)
    common.vertex_group(source, "Body", lambda co: not in_head(co))
    common.paint_region(source, head, common.SECOND_COLOR)
    cube = common.duplicate(source, "All Cube")
    dodecahedron = common.duplicate(source, "All Dodecahedron")
    both = common.duplicate(source, "Head and Body")
    common.stylize(cube, [dict(preset='CUBE')], lam=LAMBDA, iterations=STEPS)
    common.stylize(dodecahedron, [dict(preset='DODECAHEDRON')], lam=LAMBDA, iterations=STEPS)
    common.stylize(both, [dict(name="Body", preset='CUBE', vertex_group="Body"),
                          dict(name="Head", preset='DODECAHEDRON', vertex_group="Head")],
                   lam=LAMBDA, iterations=STEPS)
    objects = [source, cube, dodecahedron, both]
    common.place_grid(objects, columns=2, spacing_x=2.7, spacing_z=2.7)
    for obj, text in zip(objects, ["Groups Head (blue), Body", "Cube everywhere",
                                   "Dodecahedron everywhere", "Head: dodecahedron\nBody: cube"]):
        common.label(obj, text)


if __name__ == "__main__":
    common.run(globals())
