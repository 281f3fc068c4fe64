"""Set-ups of big meshes off Blender's main thread:
progress while the solver is prepared, Esc (cancel) stops it at once with nothing changed, and
a Pin Group changed during a live run re-factors on the worker thread too."""

import re
import threading
import time

import bmesh
import numpy as np

import helpers

THREAD = "Gauss Stylize set-up"


def _grid(cuts, name="Grid"):
    """A flat grid of about cuts**2 vertices, wavy so it has something to stylize."""
    bm = bmesh.new()
    bmesh.ops.create_grid(bm, x_segments=cuts, y_segments=cuts, size=1.0)
    for vertex in bm.verts:
        vertex.co.z = 0.1 * np.sin(6.0 * vertex.co.x) * np.cos(5.0 * vertex.co.y)
    return helpers.object_from_bmesh(bm, name)


class _Reports:
    def __init__(self):
        self.lines = []

    def report(self, kind, text):
        self.lines.append(text)


def _setup_threads():
    return [thread for thread in threading.enumerate() if thread.name == THREAD]


def _wait(predicate, limit=120.0):
    deadline = time.monotonic() + limit
    while not predicate() and time.monotonic() < deadline:
        time.sleep(0.01)


def test_a_big_set_up_runs_beside_the_main_thread_reports_progress_and_cancels_at_once(addon):
    obj = _grid(600)
    start = helpers.coords(obj)
    planned = addon.run.targets.plan_objects(_Reports(), [obj])
    live = addon.run.live_run.LiveRun(planned)
    assert live.setup.text() == "Preparing {:,} vertices".format(len(start))
    fractions, naps = [], 0
    began = time.monotonic()
    while time.monotonic() - began < 0.6 and not live.setup.done:
        time.sleep(0.01)  # the main thread runs Python meanwhile: the set-up does not hold the GIL
        naps += 1
        fractions.append(live.setup.fraction)
    assert not live.setup.done, "the set-up was too quick to be cancelled; use a bigger mesh"
    assert naps >= 20, "the main thread was blocked during the set-up (%d naps in 0.6 s)" % naps
    assert all(f is not None and 0.0 <= f <= 1.0 for f in fractions) and fractions == sorted(fractions)
    asked = time.monotonic()
    live.cancel()
    # gauss_core checks for a cancel every few milliseconds of work (0.2-0.3 s measured on a
    # 491K grid here, busy); the whole set-up takes seconds.
    assert time.monotonic() - asked < 3.0 and not _setup_threads()
    assert live.setup is None and len(obj.gauss_stylization.styles) == 0  # its default style taken back
    assert np.array_equal(helpers.coords(obj), start) and obj.data.shape_keys is None


def test_a_scripted_set_up_prints_its_progress_in_background(addon, capfd):
    obj = _grid(600)
    capfd.readouterr()
    assert helpers.stylize(1) == {'FINISHED'}
    out = capfd.readouterr().out
    percentages = [int(p) for p in re.findall(r"Gauss Stylize: Preparing %s vertices\.\.\. (\d+)%%"
                                              % "{:,}".format(len(obj.data.vertices)), out)]
    assert len(percentages) >= 3 and percentages == sorted(percentages) and percentages[-1] == 100, out


def test_a_pin_group_changed_during_a_live_run_is_prepared_beside_it(addon):
    obj = _grid(300)
    start = helpers.coords(obj)
    corner = np.flatnonzero((start[:, 0] > 0.5) & (start[:, 1] > 0.5))
    helpers.add_group(obj, "Corner", corner)
    live = addon.run.live_run.LiveRun(addon.run.targets.plan_objects(_Reports(), [obj]))
    _wait(lambda: live.setup.done)
    assert live.finish_setup() == []
    session = live.sessions[0]
    live.tick()
    factorizations = session.solver.factorization_count
    obj.gauss_stylization.pin_group = "Corner"
    live.tick()
    assert session.busy is not None and "Preparing the new pins" in live.status_text()
    steps = session.steps
    live.tick()  # no step while the solver is re-factored
    assert session.steps == steps
    _wait(lambda: session.busy is None)
    live.tick()
    live.tick()
    assert session.solver.factorization_count > factorizations and session.steps == steps + 2
    held = helpers.coords(obj)[corner]
    live.tick()
    assert np.array_equal(helpers.coords(obj)[corner], held)  # the new pins hold
    obj.gauss_stylization.pin_group = ""
    live.tick()
    assert session.busy is not None
    live.cancel()  # during the re-factorization: stops it, restores the mesh
    assert not _setup_threads() and np.array_equal(helpers.coords(obj), start)
