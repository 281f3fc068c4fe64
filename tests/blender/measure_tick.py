"""Median cost of one modal tick on the 35K bunny, headless.

    blender -b --factory-startup -P tests/blender/measure_tick.py -- BUILD_DIR [MESH] [TICKS]

A tick is what OBJECT_OT_gauss_stylize does on each timer event (live_run.LiveRun.tick):
apply changed settings (none here), one solver step, vertices_into the preallocated
buffer, the bounds check, foreach_set into the mesh, mesh.update(). The redraw request (area.tag_redraw)
is free without a window; the windowed driver reports live ticks too.
Prints a line "median tick ms: X (step: Y, write-back: Z)". No assertion:
timing depends on the machine.
"""

import os
import statistics
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


class Reports:
    """Where the planning reports go (an operator's report() in the add-on)."""

    def report(self, kind, text):
        print("%s: %s" % (next(iter(kind)).title(), text))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    build = os.path.abspath(argv[0] if argv else os.path.join(REPO, "build"))
    mesh = argv[1] if len(argv) > 1 else "bunny/bun_zipper_35947.obj"
    ticks = int(argv[2]) if len(argv) > 2 else 60
    sys.path.insert(0, os.path.join(build, "addon"))
    import gauss_stylization
    gauss_stylization.register()
    bpy.ops.wm.obj_import(filepath=os.path.join(REPO, "..", "shared", "meshes", mesh))
    obj = bpy.context.selected_objects[0]
    bpy.context.view_layer.objects.active = obj
    # The smallest Tolerance, so every tick measured takes a step (a converged object takes none).
    schema = gauss_stylization.schema
    obj.gauss_stylization.tolerance = schema.field(schema.OBJECT, "tolerance").hard[0]

    start = time.perf_counter()
    planned = gauss_stylization.targets.plan_objects(Reports(), [obj])
    live = gauss_stylization.live_run.LiveRun(planned)  # what the modal operator runs
    live.setup.wait()
    live.finish_setup()
    setup_ms = (time.perf_counter() - start) * 1000.0
    run = live.sessions[0]
    tick_ms = []
    for _ in range(ticks):
        start = time.perf_counter()
        live.tick()
        tick_ms.append((time.perf_counter() - start) * 1000.0)
    live.cancel()
    step = statistics.median(run.step_ms)
    tick = statistics.median(tick_ms)
    print("mesh %s: %d vertices, %d solver faces, set-up %.0f ms"
          % (mesh, run.arrays.num_vertices, len(run.arrays.triangles), setup_ms))
    print("median tick ms: %.2f (step: %.2f, write-back + sync: %.2f) over %d ticks, %d threads"
          % (tick, step, tick - step, ticks, run.gauss_core.get_num_threads()))


main()
