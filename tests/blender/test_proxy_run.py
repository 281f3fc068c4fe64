"""A live run above the Proxy Threshold: on a proxy while live, at full resolution once kept.

The 6K bunny with a threshold of 2,000 stands in for a sculpt (the same path, seconds instead of
minutes): the proxy is used above the threshold and not below, the kept result takes the style as a
full-resolution run from scratch does, cancelling restores the mesh bit-exactly, pins hold.
"""

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


def _live(live):
    for _ in range(LIVE_TICKS):
        live.tick()


def _finish(live):
    """Enter on the run: the finish at full resolution, ticked until it has converged."""
    assert live.start_finish()
    deadline = time.monotonic() + LIMIT
    while not live.finished:
        assert time.monotonic() < deadline, "the finish did not converge in time"
        outcome = live.finish_tick()
        assert outcome.stopped == []
        if live.finish_setup_job is not None:
            time.sleep(0.01)


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
    while live.finish_setup_job is not None:  # Esc once the finish has stepped at full resolution
        live.finish_tick()
        time.sleep(0.01)
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
