"""Painted strength: a Region's weights scale its style's strength. Spot with a weight gradient
from the nose (1) to the tail (0), shown in bands from white (0) to blue (1); the Cube style on the
whole cow, and painted with that gradient (Other Faces: Unstyled), so the head turns into blocks
and the rump stays round. Lambda 2, 200 steps."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "paint_strength"
LAMBDA, STEPS = 2.0, 200
BANDS = 5


def gradient(obj, towards):
    """(#V,) weights rising linearly from 0 at the far end to 1 at the end ``towards`` points to."""
    along = scene_kit.coords(obj) @ np.asarray(towards, np.float32)
    return (along - along.min()) / max(float(along.max() - along.min()), 1e-9)


def paint_bands(obj, weights):
    """Colour each polygon by its mean weight in BANDS steps from white (0) to blue (1)."""
    obj.data.materials.clear()
    grey, blue = np.array((0.85, 0.86, 0.88, 1.0)), np.array(render_kit.SECOND_COLOR)
    for band in range(BANDS):
        obj.data.materials.append(render_kit.material(tuple(grey + (blue - grey) * band / (BANDS - 1))))
    for polygon in obj.data.polygons:
        mean = float(np.mean(weights[list(polygon.vertices)]))
        polygon.material_index = min(int(mean * BANDS), BANDS - 1)


def build():
    source, is_spot = scene_kit.demo_mesh(scene_kit.SPOT, "Weights")
    weights = gradient(source, scene_kit.SPOT_HEAD if is_spot else (0.0, -1.0, 0.0))  # Suzanne: her face
    group = source.vertex_groups.new(name="Strength")
    for index, weight in enumerate(weights):
        group.add([index], float(weight), 'REPLACE')
    paint_bands(source, weights)
    whole = render_kit.color(scene_kit.duplicate(source, "Cube everywhere"), render_kit.STYLIZED_COLOR)
    scene_kit.stylize(whole, [dict(preset='CUBE')], lam=LAMBDA, iterations=STEPS)
    painted = render_kit.color(scene_kit.duplicate(source, "Cube painted"), render_kit.STYLIZED_COLOR)
    scene_kit.stylize(painted, [dict(preset='CUBE', vertex_group="Strength")], lam=LAMBDA, iterations=STEPS,
                      uncovered='UNSTYLED')
    render_kit.show_grid([source, whole, painted],
                         ["Weights: nose 1 (blue), tail 0", "Cube everywhere", "Cube, strength painted\nnose to tail"],
                         columns=3, spacing_x=2.7, spacing_z=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
