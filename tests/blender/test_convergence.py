"""Stop when converged: the object's Tolerance, a scripted run of 0 steps
until converged within a step cap, and a live run that stops stepping a converged object and
resumes when something changes."""

import re

import bpy
import numpy as np

import helpers


def _kept_sessions(addon, monkeypatch):
    """The sessions scripted runs keep, as they were when kept."""
    kept = []
    keep = addon.run.session.Session.keep

    def recording(session):
        kept.append(session)
        keep(session)

    monkeypatch.setattr(addon.run.session.Session, "keep", recording)
    return kept


def _twins(levels=1):
    """Two identical Suzannes: 'Suzanne' (active, the only one selected) and 'Twin'."""
    twin = helpers.suzanne(levels=levels)
    twin.name = "Twin"
    obj = helpers.suzanne(levels=levels)
    obj.name = "Suzanne"
    assert np.array_equal(helpers.coords(obj), helpers.coords(twin))
    return obj, twin


def test_tolerance_comes_from_the_solver(addon):
    gauss_core = addon.native.core()
    field = addon.settings.schema.field(addon.settings.schema.OBJECT, "tolerance")
    assert field.default == gauss_core.DEFAULTS["tolerance"]
    assert field.hard == tuple(gauss_core.LIMITS["tolerance"])
    assert field in addon.settings.schema.SOLVER_SETTERS  # a Solver keyword and a live setter


def test_zero_steps_run_until_the_tolerance_is_reached(addon, monkeypatch, capfd):
    obj, twin = _twins()
    kept = _kept_sessions(addon, monkeypatch)
    assert helpers.stylize(0, tolerance=2e-3) == {'FINISHED'}
    session = kept[-1]
    steps = session.steps
    assert session.solver.tolerance == np.float32(2e-3)
    assert session.solver.last_reldv < session.solver.tolerance and session.converged
    assert 1 < steps < addon.settings.schema.UNTIL_CONVERGED_CAP
    assert "'Suzanne' converged after %d steps" % steps in capfd.readouterr().out
    # It stopped at the first converged step: one step fewer is not converged, and those
    # steps (in other chunks) give the same shape.
    helpers.activate(twin)
    assert helpers.stylize(steps - 1, tolerance=2e-3) == {'FINISHED'}
    assert not kept[-1].converged
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert helpers.stylize(steps) == {'FINISHED'}
    assert np.array_equal(helpers.coords(twin), helpers.coords(obj))


def test_a_run_until_converged_stops_at_the_cap(addon, monkeypatch, capfd):
    monkeypatch.setattr(addon.settings.schema, "UNTIL_CONVERGED_CAP", 7)
    obj, twin = _twins()
    kept = _kept_sessions(addon, monkeypatch)
    assert helpers.stylize(0) == {'FINISHED'}
    assert kept[-1].steps == 7 and not kept[-1].converged
    assert "'Suzanne' did not converge within 7 steps" in capfd.readouterr().out
    helpers.activate(twin)
    assert helpers.stylize(7) == {'FINISHED'}
    assert np.array_equal(helpers.coords(twin), helpers.coords(obj))


def test_script_steps_0_means_until_converged_for_each_object(addon, monkeypatch):
    a = helpers.suzanne(levels=0)
    b = helpers.suzanne(levels=0)
    b.location.x = 3.0
    a.select_set(True)
    a.gauss_stylization.iterations = 0
    b.gauss_stylization.iterations = 5
    kept = _kept_sessions(addon, monkeypatch)
    assert bpy.ops.object.gauss_stylize() == {'FINISHED'}
    steps = {session.obj.name: (session.steps, session.converged) for session in kept}
    assert steps[b.name] == (5, False)
    assert steps[a.name][0] > 5 and steps[a.name][1]


def test_a_larger_tolerance_stops_sooner(addon, monkeypatch):
    kept = _kept_sessions(addon, monkeypatch)
    helpers.suzanne(levels=0)
    assert helpers.stylize(0, tolerance=1e-2) == {'FINISHED'}
    coarse = kept[-1].steps
    bpy.ops.object.gauss_stylize_reset()
    assert helpers.stylize(0, tolerance=1e-4) == {'FINISHED'}
    assert kept[-1].steps > coarse


def test_a_run_until_converged_prints_its_progress(addon, monkeypatch, capfd):
    monkeypatch.setattr(addon.run.progress, "SHOW_AFTER", 0.0)
    helpers.suzanne(levels=1)
    capfd.readouterr()
    assert helpers.stylize(0) == {'FINISHED'}
    out = capfd.readouterr().out
    shown = [int(m.group(1)) for m in
             re.finditer(r"Gauss Stylize: Stylizing 'Suzanne': (?:step \d+, until converged|converged).*?(\d+)%", out)]
    assert shown and shown[-1] == 100 and "converged at step" in out, out
    assert shown == sorted(shown), shown  # an estimate, but it never goes back


# -- live run ----------------------------------------------------------------------------

def _tick_until_converged(live, most=3000):
    for _ in range(most):
        live.tick(budget=1e9)
        if len(live.converged) == len(live.sessions):
            return
    raise AssertionError("not converged within %d ticks" % most)


def test_a_converged_live_run_stops_stepping_and_resumes_on_a_change(addon):
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE')
    live = helpers.live_run([obj])
    session = live.sessions[0]
    try:
        _tick_until_converged(live)
        steps = session.steps
        assert session.solver.last_reldv < session.solver.tolerance
        assert "Converged" in live.status_text() and live.panel_title() == "Converged"
        assert ("Suzanne: converged, step %d" % steps, 'CHECKMARK') in live.panel_lines()
        shape = helpers.coords(obj)
        for _ in range(5):
            assert live.tick(budget=1e9).stepped == 0
        assert session.steps == steps and np.array_equal(helpers.coords(obj), shape)
        # A larger tolerance changes nothing; a smaller one (below the last reldV) resumes.
        obj.gauss_stylization.tolerance = 0.5
        assert live.tick(budget=1e9).stepped == 0 and session.steps == steps
        obj.gauss_stylization.tolerance = 1e-5
        assert live.tick(budget=1e9).stepped == 1 and session.steps == steps + 1
        assert "Converged" not in live.status_text() and live.panel_title() == "Stylizing live"
        obj.gauss_stylization.tolerance = 0.5
        live.tick(budget=1e9)
        assert live.tick(budget=1e9).stepped == 0
        # A tolerance lowered but still above the last step's reldV keeps the object converged (the
        # accelerated step after the resume can end above 1e-3, so the value is taken from the run).
        reldv = session.solver.last_reldv
        obj.gauss_stylization.tolerance = min(0.4, max(2.0 * reldv, 1e-4))
        assert live.tick(budget=1e9).stepped == 0 and session.solver.last_reldv == reldv
        steps = session.steps
        # Sigma changed in the sidebar: the object steps again by itself, until it converges again.
        obj.gauss_stylization.styles[0].sigma = 9.0
        assert live.tick(budget=1e9).stepped == 1 and session.steps == steps + 1
        assert session not in live.converged
    finally:
        live.cancel()


def test_a_converged_object_waits_while_the_others_step(addon):
    a = helpers.suzanne(levels=0)
    b = helpers.suzanne(levels=1)
    b.location.x = 3.0
    a.select_set(True)
    b.gauss_stylization.tolerance = 1e-5  # converges much later
    live = helpers.live_run([a, b])
    first, second = live.sessions
    try:
        for _ in range(3000):
            live.tick(budget=1e9)
            if first in live.converged:
                break
        steps, others = first.steps, second.steps
        live.tick(budget=1e9)
        live.tick(budget=1e9)
        assert first.steps == steps and second in live.sessions and second not in live.converged
        assert second.steps == others + 2  # the other object went on stepping, one step a tick
        assert "Converged: 'Suzanne'" in live.status_text()
    finally:
        live.cancel()
