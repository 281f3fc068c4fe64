"""A live run above the Proxy Threshold: on a proxy while live, at full resolution once kept.

The 6K bunny with a threshold of 2,000 stands in for a sculpt (the same path, seconds instead of
minutes): the proxy is used above the threshold and not below, the kept result takes the style as a
full-resolution run from scratch does, cancelling restores the mesh bit-exactly, pins hold.
"""

import threading
import time

import numpy as np

import helpers
from helpers import AXES

BUNNY = "bunny/bunny_cubicstylization_6172.obj"
THRESHOLD = 2000
LIVE_TICKS = 40
LIMIT = 120.0  # seconds a set-up or a finish may take before the test gives up


def _bunny(addon, threshold=THRESHOLD):
    obj = helpers.import_obj(BUNNY)
    settings = obj.gauss_stylization
    addon.run.session.ensure_style_slot(settings)
    settings.lam = 4.0
    settings.proxy_threshold = threshold
    return obj


def _tick_until(done, tick, what="the run did not get there in time"):
    """Calls ``tick`` (a tick of the run, as the modal operator's timer gives them) until ``done()``,
    within LIMIT seconds: the proxy's steps run on a worker, so a tick returns at once."""
    deadline = time.monotonic() + LIMIT
    while not done():
        assert time.monotonic() < deadline, what
        tick()
        time.sleep(0.001)


def _no_stop(outcome):
    assert outcome.stopped == []


def _live(live, steps=LIVE_TICKS):
    """Ticks until the run on a proxy has taken ``steps`` more steps or has come to rest."""
    session = live.sessions[0]
    wanted = session.steps + steps
    _tick_until(lambda: session.steps >= wanted or (session.at_rest and not session.stepping),
                lambda: _no_stop(live.tick()), "the run did not step in time")


def _pin_the_bottom(obj, start):
    """A Pin Group of the bunny's lowest tenth."""
    helpers.add_group(obj, "Pins", np.flatnonzero(start[:, 2] - start[:, 2].min() < 0.1 * np.ptp(start[:, 2])))
    obj.gauss_stylization.pin_group = "Pins"


def _finish(live):
    """Enter on the run: the finish at full resolution, ticked until it has converged."""
    assert live.start_finish()
    _tick_until(lambda: live.finished, lambda: _no_stop(live.finish_tick()), "the finish did not converge in time")


class GatedSolver:
    """A session's solver whose steps wait while the test holds ``gate`` closed (at most WAIT seconds,
    then ``waited_out``), or raise ``fails``: what a test sees of a step in flight. Everything else is
    the solver's. Put in before the run's first step (_gated_run): the worker keeps the solver it
    started with."""

    WAIT = 5.0

    def __init__(self, solver):
        gate = threading.Event()
        gate.set()
        for name, value in (("_inner", solver), ("gate", gate), ("entered", threading.Event()),
                            ("waited_out", False), ("fails", None)):
            object.__setattr__(self, name, value)

    def fail_with(self, exc):
        object.__setattr__(self, "fails", exc)

    def step(self, count):
        self.entered.set()
        if not self.gate.wait(self.WAIT):
            object.__setattr__(self, "waited_out", True)
        if self.fails is not None:
            raise self.fails
        self._inner.step(count)

    def __getattr__(self, name):
        return getattr(self._inner, name)

    def __setattr__(self, name, value):  # the run's setting changes (run_calls' setattr)
        setattr(self._inner, name, value)


def _gated_run(obj):
    live = helpers.live_run([obj])
    session = live.sessions[0]
    gated = GatedSolver(session.solver)
    session.solver = gated
    return live, session, gated


def _hold_a_step(live, session, gated):
    """Tick until a step runs on the worker and waits at the closed gate (the ticks return meanwhile)."""
    _tick_until(lambda: not session.stepping, lambda: None)
    gated.gate.clear()
    gated.entered.clear()
    _tick_until(gated.entered.is_set, live.tick)
    assert session.stepping and not gated.waited_out


def test_a_mesh_above_the_threshold_runs_on_a_proxy_and_one_below_does_not(addon):
    obj = _bunny(addon)
    live = helpers.live_run([obj])
    session = live.sessions[0]
    assert session.on_proxy
    assert session.proxy.num_vertices < len(obj.data.vertices)
    assert len(session.solver.vertices) == session.proxy.num_vertices
    _live(live)
    assert "on a proxy of %s vertices" % "{:,}".format(session.proxy.num_vertices) in live.status_text()
    # The whole mesh follows every tick: every vertex moved, finite and bounded.
    moved = helpers.coords(obj)
    start = session.arrays.coords
    assert np.isfinite(moved).all()
    assert np.abs(moved - start).max() < np.ptp(start, axis=0).max()
    assert (np.linalg.norm(moved - start, axis=1) > 0).mean() > 0.99
    live.cancel()

    below = _bunny(addon, threshold=len(obj.data.vertices))
    live = helpers.live_run([below])
    assert not live.sessions[0].on_proxy
    assert len(live.sessions[0].solver.vertices) == len(below.data.vertices)
    assert "proxy" not in live.status_text()
    assert not live.start_finish()  # nothing to finish: Enter keeps at once
    live.cancel()


def test_the_kept_result_takes_the_style_as_a_full_resolution_run_does(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    live = helpers.live_run([obj])
    _live(live)
    _finish(live)
    session = live.sessions[0]
    assert not session.on_proxy and session.converged
    assert len(session.solver.vertices) == len(start)
    live.keep()
    kept = helpers.coords(obj)
    assert np.isfinite(kept).all()
    assert np.abs(kept - start).max() < np.ptp(start, axis=0).max()

    scratch_obj = _bunny(addon)
    scratch = addon.run.session.Session(scratch_obj)
    scratch.step_until(addon.settings.schema.UNTIL_CONVERGED_CAP)
    assert scratch.converged
    shares = [helpers.aligned_share(obj, AXES, positions=x) for x in (scratch.result, kept)]
    assert abs(shares[0] - shares[1]) <= 0.02, shares
    assert shares[0] > helpers.aligned_share(obj, AXES, positions=start) + 0.1  # the style took
    scratch.cancel()


def test_cancel_restores_the_mesh_exactly_live_and_while_finishing(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    live = helpers.live_run([obj])
    _live(live)
    live.cancel()
    assert np.array_equal(helpers.coords(obj), start)

    live = helpers.live_run([obj])
    _live(live)
    assert live.start_finish()
    # Esc once the finish has stepped at full resolution
    _tick_until(lambda: live.finish_setup_job is None, live.finish_tick)
    live.finish_tick()
    assert not np.array_equal(helpers.coords(obj), start)
    live.cancel()
    assert np.array_equal(helpers.coords(obj), start)

    live = helpers.live_run([obj])  # and while its solver is being set up
    _live(live)
    assert live.start_finish()
    live.cancel()
    assert np.array_equal(helpers.coords(obj), start)


def test_pins_act_on_the_proxy_and_hold_on_the_whole_mesh(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    low = start[:, 2] - start[:, 2].min() < 0.1 * np.ptp(start[:, 2])  # the bunny's base, a few hundred
    pinned = np.flatnonzero(low)
    helpers.add_group(obj, "Pins", pinned)
    obj.gauss_stylization.pin_group = "Pins"
    live = helpers.live_run([obj])
    session = live.sessions[0]
    assert session.on_proxy
    # Every proxy vertex that is a pinned vertex is pinned; the others pinned are the nearest corners of
    # pinned vertices the proxy does not have, along the group's edge.
    pinned_on_proxy = np.asarray(session.proxy.fine[np.asarray(session.solver.pinned)])
    kept_pins = np.intersect1d(pinned, session.proxy.fine)
    assert len(kept_pins) and np.isin(kept_pins, pinned_on_proxy).all()
    assert np.isin(pinned_on_proxy, pinned).mean() > 0.8
    _live(live)
    _finish(live)
    live.keep()
    kept = helpers.coords(obj)
    assert np.abs(kept[pinned] - start[pinned]).max() < 1e-5
    assert np.abs(np.delete(kept, pinned, axis=0) - np.delete(start, pinned, axis=0)).max() > 1e-2


def test_a_handle_drag_on_the_proxy_carries_the_whole_meshs_pins(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    low = start[:, 2] - start[:, 2].min() < 0.1 * np.ptp(start[:, 2])
    pinned = np.flatnonzero(low)
    helpers.add_group(obj, "Pins", pinned)
    obj.gauss_stylization.pin_group = "Pins"
    live = helpers.live_run([obj])
    session = live.sessions[0]
    shift = np.array([0.0, 0.0, 0.02 * np.ptp(start[:, 2])])
    session.move_pins(np.asarray(session.solver.pin_positions) + shift)
    _live(live)
    _finish(live)
    live.keep()
    kept = helpers.coords(obj)
    assert np.abs(kept[pinned] - (start[pinned] + shift)).max() < 1e-5


def test_a_region_acts_on_the_proxy_as_painted_on_the_whole_mesh(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    middle, height = np.median(start[:, 2]), np.ptp(start[:, 2])
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > middle))
    obj.gauss_stylization.uncovered = 'UNSTYLED'
    obj.gauss_stylization.styles[0].vertex_group = "Top"
    live = helpers.live_run([obj])
    session = live.sessions[0]
    weights = session.proxy.face_weights(session.arrays.triangles, session.plan.regions[0])[:, 0]
    centres = session.proxy.vertices[session.proxy.triangles].mean(axis=1)[:, 2]
    assert weights[centres > middle + 0.1 * height].min() > 0.99
    assert weights[centres < middle - 0.1 * height].max() < 0.01
    _live(live)
    moved = np.linalg.norm(helpers.coords(obj) - start, axis=1)
    assert moved[start[:, 2] > middle + 0.2 * height].mean() > 2 * moved[start[:, 2] < middle - 0.2 * height].mean()
    live.cancel()


def test_the_proxy_is_never_bigger_than_the_threshold_or_the_mesh(addon):
    size = addon.run.proxy_run.proxy_size
    assert size(1_003_688, 300_000) == addon.run.proxy_run.PROXY_VERTICES
    assert size(6172, 2000) == 2000
    assert size(6172, 6172) is None and size(100, 300_000) is None
    assert size(150, 100) == 100


def test_a_new_object_kept_from_a_proxy_run_has_no_recipe_to_follow(addon):
    # Its steps were the proxy's: Follow Edits and Replay at full resolution could not give it back.
    obj = _bunny(addon)
    obj.gauss_stylization.output = 'NEW_OBJECT'
    obj.gauss_stylization.follow_edits = True
    live = helpers.live_run([obj])
    _live(live)
    _finish(live)
    live.keep()
    copy = helpers.bpy.data.objects[obj.name + "_stylized"]
    assert not addon.mesh.follow_store.has(copy)
    assert "no kept run to replay" in addon.run.replay.problem(copy)


def test_a_tick_on_a_proxy_starts_the_step_on_a_worker_and_does_not_wait_for_it(addon):
    obj = _bunny(addon)
    live, session, gated = _gated_run(obj)
    _live(live, 3)
    _hold_a_step(live, session, gated)  # on the main thread a tick would wait out the gate here
    written, steps = helpers.coords(obj), session.steps
    assert live.tick().stepped == 0  # nothing new yet: nothing written, the step goes on
    assert np.array_equal(helpers.coords(obj), written) and session.steps == steps
    assert "step %d" % steps in live.status_text()  # the status does not wait for the step either
    gated.gate.set()
    _live(live, 2)
    assert not gated.waited_out
    assert not np.array_equal(helpers.coords(obj), written)
    live.cancel()


def test_changes_made_while_a_proxy_step_runs_reach_the_solver_after_it_in_order(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    _pin_the_bottom(obj, start)
    live, session, gated = _gated_run(obj)
    _live(live, 3)
    _hold_a_step(live, session, gated)
    # While the step runs: a new Lambda and two handle moves, the second the one that stays.
    lam = gated._inner.lam
    obj.gauss_stylization.lam = 2.5
    rest = np.asarray(gated._inner.pin_positions)
    shift = np.array([0.0, 0.0, 0.01 * np.ptp(start[:, 2])])
    session.move_pins(rest + shift)
    session.move_pins(rest + 2 * shift)
    live.tick()
    assert gated._inner.lam == lam  # nothing reached the solver during its step
    assert np.array_equal(np.asarray(gated._inner.pin_positions), rest)
    steps = session.steps
    gated.gate.set()
    _tick_until(lambda: session.steps != steps, live.tick)
    assert not gated.waited_out
    assert gated._inner.lam == 2.5
    assert np.allclose(gated._inner.pin_positions, rest + 2 * shift)
    # Both moves and the setting, booked at the step they came after, the moves first (as made).
    events = session.recipe["events"][-3:]
    assert [("pins" in e, e["step"]) for e in events] == [(True, steps + 1), (True, steps + 1), (False, steps + 1)]
    live.cancel()
    assert np.array_equal(helpers.coords(obj), start)


def test_cancel_while_a_proxy_step_runs_restores_exactly(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    live, session, gated = _gated_run(obj)
    _live(live, 5)
    assert not np.array_equal(helpers.coords(obj), start)
    _hold_a_step(live, session, gated)
    threading.Timer(0.2, gated.gate.set).start()  # the step ends while Esc waits for the worker
    live.cancel()
    assert not gated.waited_out and session.stepper is None
    assert np.array_equal(helpers.coords(obj), start)
    time.sleep(0.05)
    assert np.array_equal(helpers.coords(obj), start)


def test_a_proxy_step_that_raises_stops_its_object_with_the_error(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    live, session, gated = _gated_run(obj)
    _live(live, 2)
    gated.fail_with(RuntimeError("the factor broke"))
    outcomes = []
    _tick_until(lambda: outcomes and outcomes[-1].stopped, lambda: outcomes.append(live.tick()))
    assert outcomes[-1].stopped == [(session, "the factor broke")]
    assert live.sessions == [] and session.stepper is None
    assert np.array_equal(helpers.coords(obj), start)


def test_a_save_or_a_deletion_while_a_proxy_step_runs(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    live, session, gated = _gated_run(obj)
    _live(live, 3)
    _hold_a_step(live, session, gated)
    shown = helpers.coords(obj)
    live.hold_for_save()  # save_pre: the file gets the mesh as before the run, the step goes on
    assert np.array_equal(helpers.coords(obj), start) and session.stepping
    live.resume_after_save()  # save_post: the last step written is back, not the one still running
    assert np.array_equal(helpers.coords(obj), shown)
    gated.gate.set()
    _live(live, 2)
    assert not gated.waited_out and not np.array_equal(helpers.coords(obj), shown)

    _hold_a_step(live, session, gated)
    mesh = obj.data
    helpers.bpy.data.objects.remove(obj)  # deleted mid-step: the run drops it, its worker ends
    threading.Timer(0.2, gated.gate.set).start()
    assert live.drop_gone() == [session.name]
    assert live.sessions == [] and session.stepper is None and not gated.waited_out
    assert np.array_equal(helpers.mesh_coords(mesh), start)  # restored: another object may share it


def test_weight_paint_entered_while_a_proxy_step_runs_holds_the_mesh_still(addon):
    obj = _bunny(addon)
    live, session, gated = _gated_run(obj)
    _live(live, 3)
    _hold_a_step(live, session, gated)
    shown = helpers.coords(obj)
    try:
        helpers.bpy.ops.object.mode_set(mode='WEIGHT_PAINT')  # the strokes must land where it is shown
        gated.gate.set()
        steps = session.steps
        _tick_until(lambda: session.steps != steps and not session.stepping, live.tick)
        for _ in range(5):
            live.tick()
        assert np.array_equal(helpers.coords(obj), shown) and not session.stepping
    finally:
        helpers.bpy.ops.object.mode_set(mode='OBJECT')
    _live(live, 2)  # back in Object Mode the run goes on
    assert not np.array_equal(helpers.coords(obj), shown)
    live.cancel()


def test_a_handle_move_the_solver_refuses_after_a_proxy_step_makes_the_handles_stale(addon):
    obj = _bunny(addon)
    start = helpers.coords(obj)
    _pin_the_bottom(obj, start)
    live, session, gated = _gated_run(obj)
    _live(live, 2)
    handles = addon.handles.handles.Handles(session)
    _hold_a_step(live, session, gated)
    rest = np.asarray(gated._inner.pin_positions)
    session.move_pins(rest + np.inf)  # not finite: refused, but only once the step is done
    assert handles.current()
    gated.gate.set()
    steps = session.steps
    _tick_until(lambda: session.steps != steps, live.tick)
    assert not handles.current()  # rebuilt from the solver, which kept its targets
    assert np.array_equal(np.asarray(gated._inner.pin_positions), rest)
    assert np.array_equal(addon.handles.handles.Handles(session).targets, rest)
    live.cancel()
