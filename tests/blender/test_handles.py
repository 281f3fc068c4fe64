"""Pin handles, headless: the parts of a pin group, moving a handle's targets during a
run without re-factoring, refusing what the solver refuses, and plain ARAP dragging.
(Grabbing and dragging with the mouse is tried in a real window: windowed_interactive.py.)"""

import contextlib
import json
import re
from types import SimpleNamespace

import bpy
import numpy as np
import pytest

import helpers


def _pinned_sphere(addon, lam=None, method='GAUSS'):
    """A UV sphere with two pin handles: a cap at the bottom and one at the top."""
    obj = helpers.uv_sphere(32, 16)
    z = helpers.coords(obj)[:, 2]
    helpers.add_group(obj, "Pins", np.flatnonzero((z < -0.9) | (z > 0.9)))
    helpers.add_slot(obj, 'CUBE')
    settings = {"pin_group": "Pins", "method": method}
    if lam is not None:
        settings["lam"] = lam
    helpers.settings_io.apply_dict(obj.gauss_stylization, settings)
    return obj, addon.run.session.Session(obj)


def test_each_connected_part_of_the_pins_is_one_handle(addon):
    triangles = np.array([[0, 1, 2], [2, 3, 4], [5, 6, 7], [7, 8, 9]])
    parts = addon.handles.handles.pin_parts([9, 0, 4, 7, 3, 6, 2], triangles)
    pins = np.array([9, 0, 4, 7, 3, 6, 2])
    assert [sorted(pins[p]) for p in parts] == [[6, 7, 9], [0, 2, 3, 4]]  # in the order of their first pin
    assert addon.handles.handles.pin_parts([], triangles) == []
    assert len(addon.handles.handles.pin_parts([0, 5], triangles)) == 2  # not joined by a triangle


@pytest.mark.parametrize("method", ['GAUSS', 'CUBIC'])
def test_moving_a_handle_moves_its_pins_without_refactoring_and_the_mesh_follows(addon, method):
    obj, run = _pinned_sphere(addon, method=method)
    try:
        handles = addon.handles.handles.Handles(run)
        assert len(handles.parts) == 2
        top = next(k for k, part in enumerate(handles.parts) if handles.targets[part, 2].mean() > 0)
        run.step(5)
        before = run.result.copy()
        offset = np.array([0.4, 0.0, 0.2])
        moved = handles.targets[handles.parts[top]] + offset
        assert handles.move(top, moved)
        run.step(5)
        pins = handles.pins[handles.parts[top]]
        assert np.allclose(run.result[pins], moved, atol=1e-6)  # float32 write-back of exact targets
        other = handles.pins[handles.parts[1 - top]]
        assert np.array_equal(run.result[other], before[other])  # the other handle stays
        upper = np.flatnonzero((run.arrays.coords[:, 2] > 0.5) & (run.arrays.coords[:, 2] <= 0.9))
        assert (run.result[upper, 0] - before[upper, 0]).mean() > 0.1  # the mesh near the top follows
        assert run.solver.factorization_count == 1 and run.solver.method == method.lower()
    finally:
        run.cancel()


def test_moving_a_handle_wakes_a_converged_run(addon):
    """A live run stops stepping a converged object; a moved handle must make it step again."""
    obj, run = _pinned_sphere(addon)
    try:
        run.step_until(2000)
        assert run.converged
        handles = addon.handles.handles.Handles(run)
        assert handles.move(0, handles.targets[handles.parts[0]] + 0.1)
        assert not run.converged
    finally:
        run.cancel()


def test_targets_the_solver_refuses_change_nothing(addon):
    obj, run = _pinned_sphere(addon)
    try:
        handles = addon.handles.handles.Handles(run)
        kept = handles.targets.copy()
        assert not handles.move(0, np.full((len(handles.parts[0]), 3), 1e20))
        assert np.array_equal(handles.targets, kept) and np.array_equal(run.solver.pin_positions, kept)
        run.step(2)
        assert np.isfinite(run.result).all()
    finally:
        run.cancel()


def test_cancel_after_dragging_restores_the_mesh_bit_exactly(addon):
    obj, run = _pinned_sphere(addon)
    original = helpers.coords(obj)
    handles = addon.handles.handles.Handles(run)
    for k in range(1, 6):
        assert handles.move(0, handles.targets[handles.parts[0]] + 0.05)
        run.step()
    moved = handles.parts[0]
    # The drag happened: the pins sit at their new targets in the mesh (not just a stylized shape).
    np.testing.assert_allclose(helpers.coords(obj)[handles.pins[moved]], handles.targets[moved], atol=1e-5)
    assert np.abs(handles.targets[moved] - original[handles.pins[moved]]).max() > 0.2
    run.cancel()
    assert np.array_equal(helpers.coords(obj), original)


def test_a_changed_pin_group_rebuilds_the_handles(addon):
    obj, run = _pinned_sphere(addon)
    try:
        handles = addon.handles.handles.Handles(run)
        z = run.arrays.coords[:, 2]
        helpers.add_group(obj, "Top", np.flatnonzero(z > 0.9))
        run.weights = addon.mesh_io.read_group_weights(obj)  # as if the group existed at the start
        obj.gauss_stylization.pin_group = "Top"
        assert run.sync_settings() is None
        assert not handles.current()
        assert len(addon.handles.handles.Handles(run).parts) == 1
    finally:
        run.cancel()


def test_lambda_zero_drags_as_plain_arap(addon):
    """Lambda 0 and every mu 0 both leave only the ARAP energy: the same drag settles in the
    same shape (lambda 0 gets there faster; 300 steps: 1.6e-6 apart, measured). The cubic
    method at Cubic Lambda 0 is left out: after the same 300 steps it was 2e-3 away from these."""
    results = []
    for lam, mu in ((0.0, 1.0), (4.0, 0.0)):
        obj, run = _pinned_sphere(addon, lam=lam)
        start = helpers.coords(obj)
        obj.gauss_stylization.styles[0].mu = mu
        run.sync_settings()
        handles = addon.handles.handles.Handles(run)
        top = next(k for k, part in enumerate(handles.parts) if handles.targets[part, 2].mean() > 0)
        handles.move(top, handles.targets[handles.parts[top]] + [0.5, 0.0, 0.0])
        run.step(300)
        results.append(run.result.copy())
        run.cancel()
        helpers.clear_scene()
    assert np.allclose(results[0], results[1], atol=1e-5)
    assert np.abs(results[0] - start).max() > 0.3  # the drag did move the mesh


def test_a_script_moves_handles_with_pin_targets(addon):
    obj = helpers.uv_sphere(32, 16)
    start = helpers.coords(obj)
    z = start[:, 2]
    pins = np.flatnonzero((z < -0.9) | (z > 0.9))
    helpers.add_group(obj, "Pins", pins)
    helpers.add_slot(obj, 'CUBE')
    targets = start[pins].astype(np.float64)
    targets[z[pins] > 0] += [0.5, 0.0, 0.3]  # the top cap moved, the bottom one kept
    obj.gauss_stylization.pin_group = "Pins"
    text = json.dumps({obj.name: targets.tolist()})
    assert bpy.ops.object.gauss_stylize(iterations=20, pin_targets=text) == {'FINISHED'}
    after = helpers.coords(obj)
    assert np.allclose(after[pins], targets.astype(np.float32), atol=1e-6)
    assert (after[z > 0.5, 0] - start[z > 0.5, 0]).mean() > 0.1  # the mesh near the top followed


def test_bad_pin_targets_are_refused_and_change_nothing(addon):
    obj = helpers.uv_sphere(16, 8)
    z = helpers.coords(obj)[:, 2]
    helpers.add_group(obj, "Pins", np.flatnonzero(z > 0.9))
    helpers.add_slot(obj, 'CUBE')
    obj.gauss_stylization.pin_group = "Pins"
    count = int((z > 0.9).sum())
    original = helpers.coords(obj)
    cases = [("{not json", "Unreadable pin targets"),
             (json.dumps([[0, 0, 0]]), "Unreadable pin targets"),
             (json.dumps({"Elsewhere": [[0, 0, 0]]}), "'Elsewhere', which is not being stylized"),
             (json.dumps({obj.name: [[0, 0, 0]] * (count + 1)}), "%d targets for %d pinned" % (count + 1, count)),
             (json.dumps({obj.name: [[1e30, 0, 0]] * count}), "Pin targets of '%s'" % obj.name),
             (json.dumps({obj.name: [["x", 0, 0]] * count}), "Pin targets of '%s'" % obj.name)]
    for text, message in cases:
        with pytest.raises(RuntimeError, match=re.escape(message)):
            bpy.ops.object.gauss_stylize(iterations=3, pin_targets=text)
        assert np.array_equal(helpers.coords(obj), original)


def test_targets_json_names_only_moved_pins(addon):
    obj, run = _pinned_sphere(addon)
    try:
        assert addon.run.pin_targets.targets_json([run]) == ""
        handles = addon.handles.handles.Handles(run)
        handles.move(0, handles.targets[handles.parts[0]] + 0.1)
        data = json.loads(addon.run.pin_targets.targets_json([run]))
        assert list(data) == [obj.name] and np.allclose(data[obj.name], handles.targets)
    finally:
        run.cancel()


class _Run:
    """What the live run's event handlers see of the modal operator (modal_events)."""

    def __init__(self, sessions):
        self.preparing, self.scratch, self.notes, self.ended = False, {}, {}, []
        self.live = SimpleNamespace(sessions=sessions)

    @property
    def sessions(self):
        return self.live.sessions

    def end(self, context, keep):
        self.ended.append(keep)
        return {'FINISHED'} if keep else {'CANCELLED'}

    def show_status(self, context):
        pass


def _key(kind):
    return SimpleNamespace(type=kind, value='PRESS', mouse_x=0, mouse_y=0, ctrl=False, oskey=False)


def _grab(addon, run, session, part):
    """As if a press had grabbed ``part`` of ``session``'s handles (a press needs a window)."""
    tool = addon.handles.handle_tool.tool_of(run)
    handles = tool.handles_of(session)
    tool.drag = addon.handles.handles.Drag(handles, part, SimpleNamespace(x=0, y=0), None, (0, 0))
    return tool, handles


def test_a_drag_takes_esc_and_enter_before_the_run_and_each_object_has_its_handles(addon):
    """In a run of two objects a handle of the second is dragged: Esc puts it back and Enter
    drops it without ending the run (the drag's handler comes before the run's keys); the
    first object's pins stay; once the drag is over Esc ends the run."""
    first, first_run = _pinned_sphere(addon)
    second, second_run = _pinned_sphere(addon)
    modal_events, handle_tool = addon.run.modal_events, addon.handles.handle_tool
    run = _Run([first_run, second_run])
    try:
        first_targets = first_run.solver.pin_positions.copy()
        tool, handles = _grab(addon, run, second_run, 0)
        assert tool.handles_of(first_run) is not handles
        start = handles.targets.copy()
        assert handles.move(0, handles.targets[handles.parts[0]] + [0.3, 0.0, 0.0])
        assert modal_events.dispatch(run, bpy.context, _key('ESC')) == {'RUNNING_MODAL'}
        assert run.ended == [] and tool.drag is None and not run.notes[handle_tool.NAME]
        assert np.array_equal(second_run.solver.pin_positions, start)  # put back

        tool, handles = _grab(addon, run, second_run, 0)
        moved = handles.targets[handles.parts[0]] + [0.0, 0.2, 0.0]
        assert handles.move(0, moved)
        assert modal_events.dispatch(run, bpy.context, _key('RET')) == {'RUNNING_MODAL'}
        assert run.ended == [] and tool.drag is None
        assert np.array_equal(second_run.solver.pin_positions[handles.parts[0]], moved)  # dropped there
        assert np.array_equal(first_run.solver.pin_positions, first_targets)
        assert modal_events.dispatch(run, bpy.context, _key('ESC')) == {'CANCELLED'}
        assert run.ended == [False]
    finally:
        first_run.cancel()
        second_run.cancel()


def test_while_a_handle_is_dragged_the_status_says_only_what_the_keys_do_to_it(addon):
    """Issue 26: the header showed the run's "Esc / Right-click: cancel" beside the drag's "Esc /
    right-click: put back", and was cut off. During a drag it now says the drag's keys alone."""
    obj, session = _pinned_sphere(addon)
    run = _Run([session])
    run.live = addon.run.live_run.LiveRun.__new__(addon.run.live_run.LiveRun)  # status_text() is not asked
    status_line = addon.operators.OBJECT_OT_gauss_stylize.status_line
    key_hints = addon.operators.KEY_HINTS
    run.key_hints = lambda: key_hints
    try:
        tool, _handles = _grab(addon, run, session, 0)
        addon.handles.handle_tool._show_hint(run, bpy.context, tool)
        for axis in (None, 'Z', 'Z'):
            if axis:
                tool.drag.constrain(axis)
                addon.handles.handle_tool._show_hint(run, bpy.context, tool)
            text = status_line(run)
            assert text.count("Esc") == 1 and "put back" in text and "cancel" not in text, text
            assert not any(hint in text for hint in key_hints), text  # (its width: windowed_interactive.py)
        tool.drop()
        addon.handles.handle_tool._show_hint(run, bpy.context, tool)
        run.live = helpers.live_run([helpers.suzanne(levels=0)])  # after the drag: the run's own keys again
        assert all(hint in status_line(run) for hint in key_hints)
        run.live.cancel()
    finally:
        session.cancel()


def test_a_drag_ends_with_its_run_or_its_object(addon):
    obj, session = _pinned_sphere(addon)
    run = _Run([session])
    try:
        tool, _handles = _grab(addon, run, session, 0)
        addon.run.modal_events.run_ended(run, bpy.context, keep=True)  # on_end
        assert tool.drag is None
        tool, _handles = _grab(addon, run, session, 0)
        bpy.data.objects.remove(obj)
        assert addon.run.modal_events.dispatch(run, bpy.context, _key('ESC')) == {'CANCELLED'}
        assert tool.drag is None and run.ended == [False]
    finally:
        session.cancel()


class _SolverWithoutPinReads:
    """A session's solver whose pin arrays must not be read: each read copies them."""

    def __init__(self, solver):
        self._solver = solver

    def __getattr__(self, name):
        if name in ("pinned", "pin_positions"):
            raise AssertionError("the solver's %s was read" % name)
        return getattr(self._solver, name)


def _draw_pins(addon, monkeypatch):
    """The pin dots draw_pins() draws, as [(colour, N by 3 points)] (the gpu calls left out: no GPU
    in the background)."""
    drawn = []
    matrix = SimpleNamespace(push_pop=contextlib.nullcontext, multiply_matrix=lambda _matrix: None)
    state = SimpleNamespace(depth_test_set=lambda _mode: None, blend_set=lambda _mode: None)
    monkeypatch.setattr(addon.handles.handle_tool, "gpu", SimpleNamespace(matrix=matrix, state=state))
    monkeypatch.setattr(addon.handles.handle_tool.gpu_compat, "draw_points",
                        lambda points, colour, _size: drawn.append((colour, np.array(points))) if len(points) else None)
    addon.handles.handle_tool.draw_pins()
    return drawn


def _dots(drawn, colour):
    return np.concatenate([points for c, points in drawn if c == colour] or [np.empty((0, 3))])


def test_the_dots_are_drawn_from_the_drag_without_reading_the_solver(addon, monkeypatch):
    """At every redraw of a drag the dots come from the handles' own targets: not a copy of the
    solver's arrays. They show where the drag moved the pins, the grabbed handle's brighter."""
    handle_tool = addon.handles.handle_tool
    obj, session = _pinned_sphere(addon)
    run = _Run([session])
    addon.run.runs.start([obj], run)
    solver = session.solver
    try:
        tool, handles = _grab(addon, run, session, 0)
        moved = handles.targets[handles.parts[0]] + [0.3, 0.0, 0.1]
        assert handles.move(0, moved)
        expected = solver.pin_positions.astype(np.float32)  # where the solver has the pins now
        session.solver = _SolverWithoutPinReads(solver)
        for _redraw in range(2):
            drawn = _draw_pins(addon, monkeypatch)
            assert tool.handles_of(session) is handles  # nothing rebuilt from the solver
            outlines = _dots(drawn, handle_tool.EDGE)
            assert sorted(map(tuple, outlines)) == sorted(map(tuple, expected))
            np.testing.assert_array_equal(_dots(drawn, handle_tool.GRABBED), moved.astype(np.float32))
            np.testing.assert_array_equal(_dots(drawn, handle_tool.PIN), expected[handles.parts[1]])
        tool.drop()
        drawn = _draw_pins(addon, monkeypatch)
        assert len(_dots(drawn, handle_tool.GRABBED)) == 0 and len(_dots(drawn, handle_tool.PIN)) == len(expected)
    finally:
        session.solver = solver
        addon.run.runs.forget(run)
        session.cancel()


def test_the_dots_of_a_live_run_are_drawn_beside_a_bake(addon, monkeypatch):
    """A bake registers as a run without sessions (or a scratch dict): the pins of a Stylize run
    going on at the same time are still drawn."""
    class Bake:  # what runs.py sees of OBJECT_OT_gauss_bake_animation
        sessions = ()

    baked, bake = helpers.uv_sphere(8, 4), Bake()
    obj, session = _pinned_sphere(addon)
    run = _Run([session])
    addon.run.runs.start([baked], bake)
    addon.run.runs.start([obj], run)
    try:
        drawn = _draw_pins(addon, monkeypatch)
        assert len(_dots(drawn, addon.handles.handle_tool.PIN)) == len(session.solver.pinned)
    finally:
        addon.run.runs.forget(run)
        addon.run.runs.forget(bake)
        session.cancel()
