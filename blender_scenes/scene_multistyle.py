"""Two styles on one mesh by vertex groups (paper Section 5.1, Fig. 14): the head
(group "Head", blue) prefers dodecahedron normals, the body (group "Body") cube normals.
Left to right: the regions, all Cube, all Dodecahedron, both. Lambda 8, 200 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "multistyle"
LAMBDA, STEPS = 8.0, 200


def build():
    source, is_spot = scene_kit.demo_mesh(scene_kit.SPOT, "Regions")
    render_kit.color(source, render_kit.STYLIZED_COLOR)
    if is_spot:
        def in_head(co):
            return co[:, :2] @ scene_kit.SPOT_HEAD[:2] > 0.4
    else:  # Suzanne: the upper half
        def in_head(co):
            return co[:, 2] > 0.8
    head = scene_kit.vertex_group(source, "Head", in_head)
    scene_kit.vertex_group(source, "Body", lambda co: ~in_head(co))
    render_kit.paint_region(source, head, render_kit.SECOND_COLOR)
    variants = [("All Cube", [dict(preset='CUBE')]),
                ("All Dodecahedron", [dict(preset='DODECAHEDRON')]),
                ("Head and Body", [dict(name="Body", preset='CUBE', vertex_group="Body"),
                                   dict(name="Head", preset='DODECAHEDRON', vertex_group="Head")])]
    objects = [source]
    for name, styles in variants:
        objects.append(scene_kit.duplicate(source, name))
        scene_kit.stylize(objects[-1], styles, lam=LAMBDA, iterations=STEPS)
    render_kit.show_grid(objects, ["Groups Head (blue), Body", "Cube everywhere",
                                   "Dodecahedron everywhere", "Head: dodecahedron\nBody: cube"],
                         columns=2, spacing_x=2.7, spacing_z=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
