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

A mesh above its Proxy Threshold runs on a proxy, as a live run does (docs/interactive.md,
Sculpt-sized meshes): the set-up includes making the proxy, and the line says its size. Its steps
run on a worker thread (run/proxy_stepper.py), so a tick no longer contains a step: ticks come every
live_run.TICK_SECONDS, as the modal operator's timer gives them, and most find the step still running
and return at once. TICKS then counts the ticks that write a new state (the write into the mesh,
the settings' sync and the start of the next step; the transfer to the whole mesh is the worker's),
and "median tick ms" is theirs; the line adds the worker's step and transfer, the ticks that found it
running, and the proxy steps per second the run made (what the artist sees move).

--finish: after the ticks, what Enter does on a proxy run: the full-resolution finish from the
transfer until converged at the default Tolerance. Prints "finish ms: X (set-up: S, N steps)" and
the process's peak memory.
"""

import os
import resource
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
    drag, finish = "--drag" in argv, "--finish" in argv
    argv = [a for a in argv if a not in ("--drag", "--finish")]
    build = os.path.abspath(argv[0] if argv else os.path.join(REPO, "build"))
    mesh = argv[1] if len(argv) > 1 else "bunny/bun_zipper_35947.obj"
    ticks = int(argv[2]) if len(argv) > 2 else 60
    sys.path.insert(0, os.path.join(build, "addon"))
    import gauss_stylization
    gauss_stylization.register()
    path = mesh if os.path.isfile(mesh) else os.path.join(REPO, "..", "shared", "meshes", mesh)
    if not os.path.isfile(path):
        sys.exit("measure_tick: no mesh %s (a path, or one relative to ../shared/meshes)" % mesh)
    bpy.ops.wm.obj_import(filepath=path)
    obj = bpy.context.selected_objects[0]
    bpy.context.view_layer.objects.active = obj
    # The smallest Tolerance, so every tick measured takes a step (a converged object takes none).
    schema = gauss_stylization.settings.schema
    obj.gauss_stylization.tolerance = schema.field(schema.OBJECT, "tolerance").hard[0]

    if drag:
        pin_top_and_bottom(obj)
    start, cpu = time.perf_counter(), time.process_time()
    planned = gauss_stylization.run.targets.plan_objects(Reports(), [obj])
    live = gauss_stylization.run.live_run.LiveRun(planned)  # what the modal operator runs
    live.setup.wait()
    live.finish_setup()
    setup_ms = (time.perf_counter() - start) * 1000.0
    setup_cpu = time.process_time() - cpu  # every thread's: on a loaded machine the wall time says little
    run = live.sessions[0]
    handles = gauss_stylization.handles.handles.Handles(run) if drag else None
    tick_ms, move_ms, held_ms, waiting_ms = [], [], [], []
    interval = gauss_stylization.run.live_run.TICK_SECONDS
    on_proxy = run.on_proxy  # until the finish (--finish) goes on at full resolution
    written, steps_before, run_start = 0, run.steps, time.perf_counter()
    while written < ticks:
        # Dragging: blocks of DRAG_BLOCK ticks that move the top handle every tick, between blocks
        # that hold it, so the two are measured alternately under the same machine load.
        dragging = handles is not None and (written // DRAG_BLOCK) % 2 == 1
        start = time.perf_counter()
        if dragging:  # the mouse moved since the last tick
            top = handles.parts[-1]
            handles.move(len(handles.parts) - 1, handles.targets[top] + [0.0005, 0.0, 0.0])
            move_ms.append((time.perf_counter() - start) * 1000.0)
        outcome = live.tick()
        elapsed = time.perf_counter() - start
        if on_proxy and not outcome.stepped:  # its step still running on the worker: nothing written
            waiting_ms.append(elapsed * 1000.0)
            if run.at_rest and not (run.stepping or run.step_done):  # converged: no step will come
                break
        else:
            written += 1
            (tick_ms if handles is None or dragging else held_ms).append(elapsed * 1000.0)
        if on_proxy:  # the next timer event (a run at full resolution steps in every tick anyway)
            time.sleep(max(interval - elapsed, 0.0))
    steps_per_second = (run.steps - steps_before) / (time.perf_counter() - run_start)
    step = statistics.median(run.step_ms)
    tick = statistics.median(tick_ms)
    proxy = " on a proxy of %d vertices" % run.proxy.num_vertices if run.on_proxy else ""
    if finish:
        finish_run(live, schema)
    live.cancel()
    print("mesh %s: %d vertices, %d solver faces, set-up %.0f ms (%.1f s CPU)%s"
          % (mesh, run.arrays.num_vertices, len(run.arrays.triangles), setup_ms, setup_cpu, proxy))
    if handles is None and on_proxy:
        print("median tick ms: %.2f (a tick that writes a new state: the write into the mesh and the sync; "
              "the proxy's step and its transfer, on a worker: %.2f) over %d ticks; %d ticks found the step "
              "running (median %.3f ms); %.1f proxy steps per second; %d threads"
              % (tick, step, len(tick_ms), len(waiting_ms), statistics.median(waiting_ms) if waiting_ms else 0.0,
                 steps_per_second, run.gauss_core.get_num_threads()))
        return
    if handles is None:
        print("median tick ms: %.2f (step: %.2f, write-back + sync: %.2f) over %d ticks, %d threads; "
              "%.1f steps per second" % (tick, step, tick - step, ticks, run.gauss_core.get_num_threads(),
                                         steps_per_second))
        return
    print("median drag tick ms: %.2f (move: %.2f) over %d ticks; holding the handles: %.2f over %d ticks; "
          "%d threads, %d pins in %d handles, factorizations: %d"
          % (tick, statistics.median(move_ms), len(tick_ms), statistics.median(held_ms), len(held_ms),
             run.gauss_core.get_num_threads(), len(handles.pins), len(handles.parts),
             run.solver.factorization_count))


def finish_run(live, schema):
    """What Enter does on a proxy run, timed: the full-resolution set-up, then steps until converged."""
    session = live.sessions[0]
    session.obj.gauss_stylization.tolerance = schema.field(schema.OBJECT, "tolerance").default
    live.tick()  # the Tolerance reaches the run, as at any tick (or at start_finish on a proxy)
    start, cpu = time.perf_counter(), time.process_time()
    if not live.start_finish():
        print("finish: nothing to finish (the mesh ran at full resolution)")
        return
    while live.finish_setup_job is not None:
        live.finish_tick()
        time.sleep(0.01)
    setup = time.perf_counter() - start
    steps = session.steps
    while not live.finished:
        live.finish_tick()
    print("finish ms: %.0f (%.1f s CPU; set-up: %.0f ms, %d steps, converged: %s); peak memory %.2f GB"
          % ((time.perf_counter() - start) * 1000.0, time.process_time() - cpu, setup * 1000.0,
             session.steps - steps, session.converged, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6))


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
