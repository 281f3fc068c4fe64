"""What Follow Edits costs (docs/performance.md#follow-edits): on a mesh of ../shared/meshes, a kept New
Object run of STEPS steps, then an edit of its source (200 vertices moved) followed: the main thread's
share (read the source, prepare the re-run, write the preview) and the worker's (the solver's set-up
and the steps), the medians of REPEATS re-runs.

    blender -b --factory-startup -P tests/blender/measure_follow.py -- BUILD_DIR [MESH] [STEPS] [REPEATS]
"""

import os
import statistics
import sys
import time

import bpy
import numpy as np

ARGV = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
os.environ["GAUSS_BUILD_DIR"] = os.path.abspath(ARGV[0] if ARGV else "build")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import helpers  # noqa: E402

MESH = ARGV[1] if len(ARGV) > 1 else "bunny/bun_zipper_35947.obj"
STEPS = int(ARGV[2]) if len(ARGV) > 2 else 20
REPEATS = int(ARGV[3]) if len(ARGV) > 3 else 3


def main():
    import gauss_stylization as addon
    addon.register()
    helpers.clear_scene()
    source = helpers.import_obj(MESH)
    helpers.add_slot(source, 'CUBE')
    source.gauss_stylization.follow_edits = True
    assert helpers.stylize(STEPS, output='NEW_OBJECT') == {'FINISHED'}
    copy = bpy.data.objects[source.name + addon.settings.schema.NEW_OBJECT_SUFFIX]
    follow, rerun = addon.run.follow, addon.run.rerun
    follow.QUIET_SECONDS = 0.0
    main_thread, setups, steps = [], [], []
    for repeat in range(REPEATS):
        coords = helpers.coords(source)
        coords[:200] += np.float32(0.002)
        helpers.mesh_io.write_vertex_coords(source.data, coords)
        helpers.mesh_io.tag_changed(source.data)
        bpy.context.view_layer.update()
        start = time.perf_counter()
        follow._tick()  # read, prepare, preview; the job starts on its worker
        main_thread.append(time.perf_counter() - start)
        follow.settle()
        plan = rerun.prepare(copy).plan  # the worker's share, timed in its parts
        start = time.perf_counter()
        solver = plan.build_solver()
        setups.append(time.perf_counter() - start)
        solver.set_styles(plan.styles)
        solver.set_face_weights(*plan.regions)
        start = time.perf_counter()
        for _step in range(STEPS):
            solver.step(1)
        steps.append(time.perf_counter() - start)
    print("follow edits on %s (%d vertices), %d steps, medians of %d: main thread %.0f ms (read, prepare, "
          "preview); worker: set-up %.0f ms + steps %.0f ms (%.1f ms a step)"
          % (MESH, len(source.data.vertices), STEPS, REPEATS, 1000 * statistics.median(main_thread),
             1000 * statistics.median(setups), 1000 * statistics.median(steps),
             1000 * statistics.median(steps) / STEPS), flush=True)


main()
