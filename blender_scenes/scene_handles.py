"""Dragging handles (paper Sections 3.3 and 5.1, Fig. 13): the cow's feet and the tips of
its horns are pinned (red); each connected part of the Pin Group is a handle. The two horn
handles are lifted and pushed forward, as a drag in the viewport does during a live run,
here given to the operator as pin targets. With lambda 0 this is plain as-rigid-as-possible
dragging; with the Cube style the cow is stylized while it follows the handle."""

import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "handles"
STEPS = 200
FEET_HEIGHT, HEAD_SHARE = 0.12, 0.08   # feet: below this height; horn tips: the top share of it
LIFT = np.array([0.0, 0.0, 0.35])       # the horn handles' move: up ...
FORWARD = 0.3                           # ... and this far the way the cow looks
FINISH = dict(camera_direction=(0.15, -1.0, 0.12))


def handles_group(source):
    """The Pin Group "Handles" (feet and horn tips). Returns (pinned, horn tip) vertex indices."""
    co = scene_kit.coords(source)
    top = co[:, 2].max()
    horns = np.flatnonzero(co[:, 2] > top - HEAD_SHARE * top)
    pins = scene_kit.vertex_group(source, "Handles",
                                  lambda c: (c[:, 2] < FEET_HEIGHT) | (c[:, 2] > top - HEAD_SHARE * top))
    return np.array(pins), horns


def dragged(source, name, pins, horns, **settings):
    """A Cube-styled copy (it keeps the vertex groups) with the horn handles moved: the Pin
    Group's new positions go to the operator as pin targets, in the group's vertex order."""
    copy = render_kit.color(scene_kit.duplicate(source, name), render_kit.STYLIZED_COLOR)
    render_kit.paint_region(copy, pins.tolist(), render_kit.PIN_COLOR)
    targets = scene_kit.coords(copy)[pins].astype(np.float64)
    targets[np.isin(pins, horns)] += LIFT + FORWARD * scene_kit.SPOT_HEAD
    scene_kit.stylize(copy, [dict(preset='CUBE')], iterations=STEPS, pin_group="Handles",
                      pin_targets=json.dumps({copy.name: targets.tolist()}), **settings)
    return copy


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.color(source, render_kit.ORIGINAL_COLOR)
    pins, horns = handles_group(source)
    render_kit.paint_region(source, pins.tolist(), render_kit.PIN_COLOR)
    arap = dragged(source, "ARAP", pins, horns, lam=0.0)
    cube = dragged(source, "Cube", pins, horns, lam=4.0)
    render_kit.show_grid([source, arap, cube],
                         ["Original\nhandles in red", "Horns dragged up\nlambda 0 (plain ARAP)",
                          "Horns dragged up\nCube style, lambda 4"], columns=3, spacing_x=2.9)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
