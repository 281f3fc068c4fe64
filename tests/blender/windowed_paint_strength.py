"""Painted strength in a real window: Weight Paint strokes during a live run are picked up when the
object returns to Object Mode. Run by run_windowed.sh, with windowed_kit.py's helpers:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_paint_strength.py -- BUILD_DIR

The test mesh's Cube slot gets a Region whose weights are all 0 (Other Faces: Unstyled), so the run
starts with nothing to stylize. The object goes to Weight Paint mode mid-run (as the header's mode
menu does it: object.mode_set), the Region is painted to 1 there, and the object goes back to Object
Mode: the run must go on while painting without reading the strokes, stylize once back, and Esc must
still restore the mesh. The summary goes to BUILD_DIR/screenshots/windowed_paint_strength_result.txt.
"""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as kit  # noqa: E402  (also sets up the paths and the window options)
from windowed_kit import check, coords, end_with, live_operator, live_run, wait_steps  # noqa: E402
import helpers  # noqa: E402

TIME_LIMIT = 600.0  # seconds: a busy 2-core machine redraws a window slowly
CUBE = np.vstack([np.eye(3), -np.eye(3)])


def unpainted_region(name):
    obj = bpy.data.objects[name]
    helpers.add_group(obj, "Paint", range(len(obj.data.vertices)), weight=0.0)
    obj.gauss_stylization.styles[0].vertex_group = "Paint"
    obj.gauss_stylization.uncovered = 'UNSTYLED'
    kit.push_undo("Paint region")


def set_mode(mode):
    with kit.override():
        bpy.ops.object.mode_set(mode=mode)


def paint_and_return(name, _prepared):
    obj = bpy.data.objects[name]
    original = coords(obj)
    rest_share = helpers.aligned_share(obj, CUBE, original)
    yield from live_run(3)
    check("a Region of weight 0 leaves the mesh unstyled",
          helpers.aligned_share(obj, CUBE) < rest_share + 0.02)
    set_mode('WEIGHT_PAINT')
    yield 0.3
    obj.vertex_groups["Paint"].add(list(range(len(original))), 1.0, 'REPLACE')  # the strokes
    op = live_operator()
    painted_at = op.session.steps if op and op.session else 0
    yield 1.0
    op = live_operator()
    check("the run goes on in Weight Paint mode without reading the strokes",
          op is not None and op.session is not None and obj.mode == 'WEIGHT_PAINT' and
          not np.any(op.session.weights["Paint"]))
    set_mode('OBJECT')
    yield 0.5  # a few ticks: the first one back reads the strokes (until then the run is still converged)
    yield from wait_steps(painted_at + 25)
    op = live_operator()
    check("back in Object Mode the run stylizes with the painted weights",
          op is not None and np.all(op.session.weights["Paint"] == 1.0) and
          helpers.aligned_share(obj, CUBE) > rest_share + 0.2,
          "share %.3f (rest %.3f)" % (helpers.aligned_share(obj, CUBE), rest_share))
    yield from end_with('ESC', "Esc after painting restores the mesh", name, original)


def run_scenario(scenario_name, name, prepared):
    return globals()[scenario_name](name, prepared)


kit.start(kit.cube_style_scenarios(("paint_and_return",), run_scenario, prepare=unpainted_region),
          "windowed_paint_strength_result.txt", time_limit=TIME_LIMIT)
