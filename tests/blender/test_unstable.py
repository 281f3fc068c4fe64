"""A mesh whose steps run away (strongly obtuse triangles at a high ADMM Iterations: the edge pull grows
the mesh, and the solver redoes such a step as plain ARAP, docs/robustness.md) stays bounded, and the
artist is told it is unstable and what to lower, live and from a script; a run that never runs away
says nothing of it."""
import bmesh
import bpy
import numpy as np

import helpers


def _spiked_cube():
    """A cube with one corner pulled four sizes down: its two long edges get negative cotangent weights."""
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    corner = min(bm.verts, key=lambda v: tuple(v.co))
    corner.co.z -= 4.3
    obj = helpers.object_from_bmesh(bm, "Spiked")
    helpers.add_slot(obj, 'CUBE')
    obj.gauss_stylization.admm_iterations = 20
    return obj


def _ticks(obj, count):
    live = helpers.live_run([obj])
    texts = []
    for _ in range(count):
        live.tick(budget=1e9)
        texts.append(live.status_text())
    session = live.sessions[0]
    coords = session.result.copy()
    live.cancel()
    return session, texts, coords


def test_a_live_run_that_runs_away_says_unstable_and_stays_bounded(addon):
    obj = _spiked_cube()
    before = helpers.coords(obj)
    live = helpers.live_run([obj])
    texts, panels = [], []
    for _ in range(60):
        live.tick(budget=1e9)
        texts.append(live.status_text())
        panels.append(live.panel_lines())
    session = live.sessions[0]
    coords = session.result.copy()
    live.cancel()
    assert session.solver.runaway_steps > 0
    said = [i for i, t in enumerate(texts) if "unstable: lower Lambda or ADMM Iterations" in t]
    assert said, texts[-1]
    # Wherever it says so, the sidebar says so too, in place of a settling figure that means nothing then.
    for i in said:
        assert ("unstable: lower Lambda or ADMM Iterations", 'ERROR') in [line[:2] for line in panels[i]]
        assert "settling" not in texts[i] and not any("settling" in line[0] for line in panels[i])
    size = np.ptp(before, axis=0).max()
    assert np.isfinite(coords).all() and np.abs(coords - before.mean(axis=0)).max() < 5 * size
    assert np.array_equal(helpers.coords(obj), before)  # cancelled: as it was


def test_a_script_run_that_runs_away_warns_unstable(addon, monkeypatch, capfd):
    monkeypatch.setattr(addon.settings.schema, "UNTIL_CONVERGED_CAP", 60)
    _spiked_cube()
    assert bpy.ops.object.gauss_stylize(iterations=0) == {'FINISHED'}
    out = capfd.readouterr().out
    assert "'Spiked' did not converge within 60 steps" in out and "unstable at these settings" in out, out


def test_a_run_that_settles_says_nothing_of_it(addon):
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'CUBE')
    session, texts, _ = _ticks(obj, 30)
    assert session.solver.runaway_steps == 0 and not session.unstable
    assert not any("unstable" in t for t in texts)
