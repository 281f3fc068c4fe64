"""Undo is off while a live run writes mid-run shapes, and the artist's undo_steps (and the
preferences' unsaved mark) come back on every way runs end. The windowed
tests (windowed_run_endings.py) end real runs by each key and click; these cover the module
state and the handlers without a window."""

import bpy
import pytest

import helpers

USER_STEPS = 47


@pytest.fixture
def preferences():
    prefs = bpy.context.preferences
    before = prefs.edit.undo_steps, prefs.is_dirty
    prefs.edit.undo_steps = USER_STEPS
    prefs.is_dirty = False
    yield prefs
    prefs.edit.undo_steps, prefs.is_dirty = before


class _Run:
    """Stands for a live run as runs.py sees one: stop() and report()."""

    def __init__(self, fail=False):
        self.stopped, self.reports, self.fail = [], [], fail

    def stop(self, context, keep):
        self.stopped.append(keep)
        if self.fail:
            raise RuntimeError("restoring failed")

    def cancel_keeping_edits(self, context):
        self.stop(context, keep=False)
        return False

    def report(self, kind, text):
        self.reports.append(text)


def test_suspend_and_resume_give_back_the_value_and_the_unsaved_mark(addon, preferences):
    guard = addon.run.undo_guard
    guard.suspend()
    guard.suspend()  # twice: still the artist's value saved, not 0
    assert preferences.edit.undo_steps == 0 and not preferences.is_dirty
    guard.resume()
    assert preferences.edit.undo_steps == USER_STEPS and not preferences.is_dirty
    guard.resume()
    assert preferences.edit.undo_steps == USER_STEPS


def test_changes_the_artist_made_during_a_run_stay(addon, preferences):
    guard = addon.run.undo_guard
    guard.suspend()
    preferences.view.ui_line_width = 'THICK'  # another preference changed meanwhile: must be saved later
    guard.resume()
    assert preferences.edit.undo_steps == USER_STEPS and preferences.is_dirty
    preferences.view.ui_line_width = 'AUTO'
    guard.suspend()
    preferences.edit.undo_steps = 12  # the artist set undo steps during the run
    guard.resume()
    assert preferences.edit.undo_steps == 12


def test_undo_is_off_exactly_while_runs_are_registered(addon, preferences):
    runs = addon.run.runs
    a, b = helpers.uv_sphere(), helpers.uv_sphere()
    first, second = _Run(), _Run()
    runs.start([a], first)
    runs.start([b], second)
    assert preferences.edit.undo_steps == 0
    runs.forget(first)
    assert preferences.edit.undo_steps == 0  # the other run is still writing
    runs.forget(second)
    assert preferences.edit.undo_steps == USER_STEPS


@pytest.mark.parametrize("handler", ["_end_runs_before_undo", "_end_runs_before_redo", "_end_runs_before_load"])
def test_undo_redo_and_loading_end_runs_and_give_undo_back(addon, preferences, handler):
    run = _Run()
    addon.run.runs.start([helpers.uv_sphere()], run)
    getattr(addon.run.runs, handler)(None)
    assert run.stopped == [False] and not addon.run.runs.running
    assert preferences.edit.undo_steps == USER_STEPS


def test_handlers_are_registered(addon):
    for name, handler in addon.run.runs.HANDLERS:
        assert handler in getattr(bpy.app.handlers, name), name


def test_undo_comes_back_even_when_ending_a_run_fails(addon, preferences):
    run = _Run(fail=True)
    addon.run.runs.start([helpers.uv_sphere()], run)
    with pytest.raises(RuntimeError, match="restoring failed"):
        addon.run.runs.stop_all(bpy.context)
    assert not addon.run.runs.running and preferences.edit.undo_steps == USER_STEPS


def test_disabling_the_addon_ends_runs_and_gives_undo_back(addon, preferences):
    run = _Run()
    addon.run.runs.start([helpers.uv_sphere()], run)
    addon.unregister()
    try:
        assert run.stopped == [False] and preferences.edit.undo_steps == USER_STEPS
    finally:
        addon.register()


def test_a_second_stylize_waits_for_the_live_run(addon, preferences):
    # Were two runs live, keeping one would push its undo step while undo is still off for the
    # other, and that step would be lost.
    run = _Run()
    addon.run.runs.start([helpers.uv_sphere()], run)
    try:
        helpers.suzanne(levels=0)
        assert not bpy.ops.object.gauss_stylize.poll()
        with pytest.raises(RuntimeError, match="already running on other objects"):
            bpy.ops.object.gauss_stylize(iterations=1)
    finally:
        addon.run.runs.forget(run)
    assert bpy.ops.object.gauss_stylize.poll()
