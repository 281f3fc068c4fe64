"""Keep Volume: stylization shrinks a shape (a limitation the paper lists); with Keep
Volume the solver scales every closed part back to its rest volume after each step, so the
stylized bunny keeps its size. Watertight bunny (34.8K vertices), Cube style, lambda 4, 100 steps."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "keep_volume"
LAMBDA, STEPS = 4.0, 100
FINISH = dict(camera_direction=(0.0, -1.0, 0.15))


def build():
    source, _ = scene_kit.demo_mesh(scene_kit.BUNNY_WATERTIGHT, "Original")
    render_kit.color(source, render_kit.ORIGINAL_COLOR)
    rest = scene_kit.volume(source)
    objects, labels = [source], ["Original"]
    for keep, name in ((False, "Keep Volume off"), (True, "Keep Volume on")):
        copy = render_kit.color(scene_kit.duplicate(source, name), render_kit.STYLIZED_COLOR)
        scene_kit.stylize(copy, [dict(preset='CUBE')], lam=LAMBDA, iterations=STEPS, keep_volume=keep)
        share = scene_kit.volume(copy) / rest
        print("  %-16s volume %.4f of the original's" % (name, share))
        objects.append(copy)
        labels.append("Cube, %s\nvolume %.1f%%" % (name.replace("Keep Volume ", "Keep Volume: "), 100 * share))
    render_kit.show_grid(objects, labels, columns=3, spacing_x=2.5)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
