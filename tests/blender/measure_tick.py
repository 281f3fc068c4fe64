"""Median cost of one modal tick on the 35K bunny, headless.

    blender -b --factory-startup -P tests/blender/measure_tick.py -- BUILD_DIR [MESH] [TICKS] [--drag]

A tick is what OBJECT_OT_gauss_stylize does on each timer event (live_run.LiveRun.tick):
apply changed settings (none here), one solver step, vertices_into the preallocated
buffer, the bounds check, foreach_set into the mesh, mesh.update(). The redraw request (area.tag_redraw)
is free without a window; the windowed driver reports live ticks too.
Prints a line "median tick ms: X (step: Y, write-back: Z)". No assertion:
timing depends on the machine.

--drag: the bunny's top (ears, 3% of its height) and bottom are pinned (its
handles), and in every other block of DRAG_BLOCK ticks one ear's handle moves a
little before each tick, as a mouse drag does (Handles.move ->
Solver.set_pin_positions); the blocks between hold it. Prints "median drag tick
ms: X (move: M) ...; holding the handles: H ...": ticks while dragging and while
holding, measured alternately under the same load.
"""

import os
import statistics
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
DRAG_BLOCK = 10  # --drag: ticks per block of moving (or holding) the handle


class Reports:
    """Where the planning reports go (an operator's report() in the add-on)."""

    def report(self, kind, text):
        print("%s: %s" % (next(iter(kind)).title(), text))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    drag = "--drag" in argv
    argv = [a for a in argv if a != "--drag"]
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
    schema = gauss_stylization.settings.schema
    obj.gauss_stylization.tolerance = schema.field(schema.OBJECT, "tolerance").hard[0]

    if drag:
        pin_top_and_bottom(obj)
    start = time.perf_counter()
    planned = gauss_stylization.run.targets.plan_objects(Reports(), [obj])
    live = gauss_stylization.run.live_run.LiveRun(planned)  # what the modal operator runs
    live.setup.wait()
    live.finish_setup()
    setup_ms = (time.perf_counter() - start) * 1000.0
    run = live.sessions[0]
    handles = gauss_stylization.handles.handles.Handles(run) if drag else None
    tick_ms, move_ms, held_ms = [], [], []
    for tick in range(ticks):
        # Dragging: blocks of DRAG_BLOCK ticks that move the top handle every tick, between blocks
        # that hold it, so the two are measured alternately under the same machine load.
        dragging = handles is not None and (tick // DRAG_BLOCK) % 2 == 1
        start = time.perf_counter()
        if dragging:  # the mouse moved since the last tick
            top = handles.parts[-1]
            handles.move(len(handles.parts) - 1, handles.targets[top] + [0.0005, 0.0, 0.0])
            move_ms.append((time.perf_counter() - start) * 1000.0)
        live.tick()
        (tick_ms if handles is None or dragging else held_ms).append((time.perf_counter() - start) * 1000.0)
    live.cancel()
    step = statistics.median(run.step_ms)
    tick = statistics.median(tick_ms)
    print("mesh %s: %d vertices, %d solver faces, set-up %.0f ms"
          % (mesh, run.arrays.num_vertices, len(run.arrays.triangles), setup_ms))
    if handles is None:
        print("median tick ms: %.2f (step: %.2f, write-back + sync: %.2f) over %d ticks, %d threads"
              % (tick, step, tick - step, ticks, run.gauss_core.get_num_threads()))
        return
    print("median drag tick ms: %.2f (move: %.2f) over %d ticks; holding the handles: %.2f over %d ticks; "
          "%d threads, %d pins in %d handles, factorizations: %d"
          % (tick, statistics.median(move_ms), len(tick_ms), statistics.median(held_ms), len(held_ms),
             run.gauss_core.get_num_threads(), len(handles.pins), len(handles.parts),
             run.solver.factorization_count))


def pin_top_and_bottom(obj, share=0.03):
    """A vertex group "Handles" of the top and bottom ``share`` of the mesh's height (its own Z...
    or Y for a Y-up scan) and the object's Pin Group set to it."""
    from gauss_stylization import mesh_io
    coords = mesh_io.read_vertex_coords(obj.data)
    up = coords[:, 1] if obj.rotation_euler[0] != 0.0 else coords[:, 2]  # OBJ import turns Y-up scans
    low, high = up.min(), up.max()
    chosen = (up < low + share * (high - low)) | (up > high - share * (high - low))
    group = obj.vertex_groups.new(name="Handles")
    group.add([int(i) for i in chosen.nonzero()[0]], 1.0, 'REPLACE')
    obj.gauss_stylization.pin_group = "Handles"


main()
