"""The live run's event handlers (modal_events): the order they are asked in, how another
feature plugs in, and that a press always starts a new click. The windowed tests drive the
real modal operator; these use stand-ins for the run and the events."""

from types import SimpleNamespace

import bpy
import pytest


class _Run:
    """What handlers see of the modal operator."""

    def __init__(self):
        self.preparing, self.scratch, self.notes, self.ended = False, {}, {}, []

    def end(self, context, keep, why=None):
        self.ended.append(keep)
        self.why = why
        return {'FINISHED'} if keep else {'CANCELLED'}


def _event(kind, value='PRESS', **more):
    keys = dict(ctrl=False, oskey=False, shift=False)
    keys.update(more)
    return SimpleNamespace(type=kind, value=value, mouse_x=10, mouse_y=10, **keys)


@pytest.fixture
def events(addon):
    added = []

    def add(handler, order, on_end=None):
        addon.run.modal_events.add(handler, order, on_end)
        added.append(handler)

    yield addon.run.modal_events, add
    for handler in added:
        addon.run.modal_events.remove(handler)


def test_keys_end_the_run_and_undo_cancels_it_saying_so(events):
    modal_events, _add = events
    run = _Run()
    assert modal_events.dispatch(run, bpy.context, _event('RET')) == {'FINISHED'}
    assert modal_events.dispatch(run, bpy.context, _event('ESC')) == {'CANCELLED'} and run.why is None
    assert modal_events.dispatch(run, bpy.context, _event('Z', ctrl=True, shift=False)) == {'CANCELLED'}
    assert "cancelled by undo" in run.why
    assert modal_events.dispatch(run, bpy.context, _event('Z', ctrl=True, shift=True)) == {'CANCELLED'}
    assert "cancelled by redo" in run.why
    assert modal_events.dispatch(run, bpy.context, _event('TAB')) == {'RUNNING_MODAL'}
    # Ctrl+Tab opens the mode pie, one of the ways to Weight Paint during a run (docs/interactive.md).
    assert modal_events.dispatch(run, bpy.context, _event('TAB', ctrl=True)) == {'PASS_THROUGH'}
    assert modal_events.dispatch(run, bpy.context, _event('G')) == {'PASS_THROUGH'}
    assert run.ended == [True, False, False, False]


def test_while_preparing_only_esc_ends_the_run(events):
    modal_events, _add = events
    run = _Run()
    run.preparing = True
    assert modal_events.dispatch(run, bpy.context, _event('RET')) == {'PASS_THROUGH'}
    assert modal_events.dispatch(run, bpy.context, _event('ESC')) == {'CANCELLED'}


def test_a_handler_added_between_keys_and_clicks_takes_presses_first(events):
    modal_events, add = events
    seen = []

    def pins(run, context, event):
        seen.append(event.type)
        return {'RUNNING_MODAL'} if event.type == 'LEFTMOUSE' else None

    add(pins, modal_events.HANDLES)
    run = _Run()
    run.scratch["click"] = (10, 10)  # as if an earlier press had been recorded by the click handler
    assert modal_events.dispatch(run, bpy.context, _event('LEFTMOUSE')) == {'RUNNING_MODAL'}
    assert "click" not in run.scratch  # a press always starts a new click
    assert modal_events.dispatch(run, bpy.context, _event('LEFTMOUSE', 'RELEASE')) == {'RUNNING_MODAL'}
    assert modal_events.dispatch(run, bpy.context, _event('ESC')) == {'CANCELLED'}  # keys come first
    assert seen == ['LEFTMOUSE', 'LEFTMOUSE']
    modal_events.remove(pins)
    assert modal_events.dispatch(run, bpy.context, _event('LEFTMOUSE', 'RELEASE')) == {'PASS_THROUGH'}


def test_on_end_hears_of_the_end_of_a_run(events):
    modal_events, add = events
    heard = []
    add(lambda run, context, event: None, modal_events.HANDLES,
        on_end=lambda run, context, keep: heard.append(keep))
    modal_events.run_ended(_Run(), bpy.context, keep=True)
    assert heard == [True]
