"""Operators: Stylize (a live modal run, or scripted steps), Reset and Replay.

Stylize acts on the active object and every other selected mesh (targets.py).
Invoked from the interface it runs live: the solvers are set up on a worker
thread (solver_setup.py) while a timer polls them, then each tick steps the
objects (live_run.py); events go through modal_events.py. The operator is the
event loop only: what it shows and what its redo panel repeats are worded by
live_run.LiveRun, and it is a run as run_interface.StylizeRun says. From a
script, in background mode and from the redo panel it runs a fixed number of
steps (scripted_run.py). Either way a kept run is one undo step.
"""

import time

import bpy
from bpy.props import StringProperty

from .errors import SettingsError
from .mesh import rest_store
from .run import modal_events, replay, runs, scripted_run
from .run.live_run import SAVED_NOTE, SAVED_REPORT, TICK_SECONDS, LiveRun
from .run.progress import ProgressReport
from .run.targets import TITLE, plan_objects, report_skipped, stylize_objects, stylize_problem
from .settings import schema, settings_io
from .settings.validation import object_problem, poll_result
from .view.viewport import existing_area, redraw_viewports

PANEL_SECONDS = 0.25  # how often a live run redraws the sidebar (the viewport: every tick that steps)
EDITS_UNDO_NAME = "Edits during Stylize"  # the undo step of what was edited during a cancelled run
_STEPS = schema.field(schema.OBJECT, "iterations")


def _idle_object_problem(context):
    """Why an operator on the active object's mesh cannot run (None if it can): no usable object, or a
    stylization running on it."""
    problem = object_problem(context)
    if problem is None and runs.is_running(context.active_object):
        problem = "Stylization is already running on this object"
    return problem


def _last_registered_operator(context):
    operators = context.window_manager.operators
    return operators[-1].as_pointer() if len(operators) else None


class OBJECT_OT_gauss_stylize(bpy.types.Operator):
    """Stylize the selected meshes live: a solver step per tick, settings apply at once.
    Enter/left-click keeps the result, Esc/right-click restores the meshes"""
    bl_idname = "object.gauss_stylize"
    bl_label = "Stylize"
    bl_options = {'REGISTER', 'UNDO'}

    # The name, range and default of the object's Script Steps, which a script run defaults to.
    iterations: _STEPS.prop({},
                            tooltip="Solver steps, 0: until converged, at most %d (scripts: defaults to each "
                                    "object's Script Steps setting)" % schema.UNTIL_CONVERGED_CAP)
    # Settings a kept live run ended with, so the redo panel repeats that run (JSON, see settings_io).
    settings_json: StringProperty(options={'HIDDEN', 'SKIP_SAVE'})
    # Where a kept live run left dragged pins, so the redo panel repeats it; scripts may set it too:
    # '{"object name": [[x, y, z], ...]}', one target per Pin Group vertex (run/pin_targets.py: targets_json).
    pin_targets: StringProperty(name="Pin Targets", options={'HIDDEN', 'SKIP_SAVE'},
                                description="New positions of the pinned vertices, JSON by object name")

    @classmethod
    def poll(cls, context):
        return poll_result(cls, stylize_problem(context))

    # -- scripted / background / redo: run synchronously ------------------------

    def execute(self, context):
        objects = stylize_objects(context)
        if self.settings_json:
            try:
                settings_io.apply_objects_json(objects, self.settings_json)
            except (ValueError, KeyError, TypeError) as exc:
                self.report({'ERROR'}, "Unreadable settings_json (%s): %s" % (type(exc).__name__, exc))
                return {'CANCELLED'}
        steps = self.iterations if self.properties.is_property_set("iterations") else None
        if steps is None:
            self.iterations = objects[0].gauss_stylization.iterations
        planned = plan_objects(self, objects)
        if planned is None:
            return {'CANCELLED'}
        return scripted_run.run(self, context, planned, steps, self.pin_targets)

    # -- interactive: modal on a timer -------------------------------------------

    def invoke(self, context, event):
        if context.window is None or bpy.app.background:
            return self.execute(context)  # no window to run live in
        planned = plan_objects(self, stylize_objects(context))
        if planned is None:
            return {'CANCELLED'}
        self.live = LiveRun(planned)
        self.scratch = {}  # event handlers' state (modal_events)
        self.notes = {}    # event handlers' status texts (modal_events)
        self._handlers_told = False  # modal_events.run_ended called
        # The area's address only, never a Python reference to it: see viewport.existing_area.
        self._area_pointer = context.area.as_pointer() if context.area else None
        self._operator_at_start = _last_registered_operator(context)
        self._operator_ran = False  # see _operators_ran()
        self._progress = ProgressReport(context, TITLE, status=False)
        self._panels_drawn = 0.0
        window_manager = context.window_manager
        self._timer = window_manager.event_timer_add(TICK_SECONDS, window=context.window)
        window_manager.modal_handler_add(self)
        runs.start(planned.objects, self)
        self.show_status(context)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if self._timer is None:
            # Already ended outside an event (undo handler, add-on disabled); the
            # handler is still there until it returns, and the event is not ours.
            return {'CANCELLED', 'PASS_THROUGH'}
        try:
            if event.type == 'TIMER':
                return self._tick(context)
            if self.live.finishing:
                return self._finishing_event(context, event)
            return modal_events.dispatch(self, context, event)
        except Exception as exc:  # never leave a half-done run or a dangling timer behind
            self.stop(context, keep=False)
            self.report({'ERROR'}, "Stylize stopped, meshes restored: %s" % exc)
            return {'CANCELLED'}

    @property
    def preparing(self):
        return self.live.preparing

    def _tick(self, context):
        live = self.live
        self._operators_ran(context)
        if live.preparing:
            if not live.setup.done:
                self._progress.update(live.setup.fraction, live.setup.text())
                self._redraw(context)
                self.show_status(context)
                return {'PASS_THROUGH'}
            self._progress.end()
            self._progress = None
            if context.mode != 'OBJECT':  # nothing was changed yet: cancel rather than keep
                self.stop(context, keep=False)
                self.report({'WARNING'}, "Stylize cancelled: the object left Object Mode while it was preparing")
                return {'CANCELLED'}
            report_skipped(self, live.finish_setup(), any_left=bool(live.sessions))
            if not live.sessions:
                self.stop(context, keep=False)
                return {'CANCELLED'}
        if live.finishing:
            return self._finish_tick(context)
        if context.mode not in {'OBJECT', 'PAINT_WEIGHT'}:
            # Edit Mode would overwrite a restore on exit, so keep what is there
            # and let Reset (which has the start coordinates) take it back. Weight Paint
            # holds the painted object still (live_run.tick) and leaves its mesh to the run.
            self.stop(context, keep=True)
            self.report({'WARNING'}, "Stylize stopped: the object left Object Mode. "
                                     "Use Reset in Object Mode to get the original back")
            return {'FINISHED'}
        outcome = live.tick()
        for session, why in outcome.stopped:
            self.report({'WARNING'}, "Stylize stopped on '%s', its mesh restored: %s" % (session.name, why))
        for name, why in outcome.paused:
            self.report({'WARNING'}, "Stylize paused on '%s': %s" % (name, why))
        if not live.sessions:  # every object deleted: that deletion must be an undo step of its own
            self.cancel_keeping_edits(context)
            return {'CANCELLED'}
        self._show_busy(context)
        if outcome.stepped or time.monotonic() - self._panels_drawn > PANEL_SECONDS:
            # Nothing stepped (converged, paused, waiting for pins): a refresh a few times a second.
            self._redraw(context)
            self.show_status(context)
        return {'PASS_THROUGH'}  # other operators may own this timer event

    def _finishing_event(self, context, event):
        """While a kept proxy run is finished at full resolution only Esc (and undo, which would
        otherwise act on a half-done run) acts: it cancels; the run's other keys and clicks wait."""
        if event.value == 'PRESS' and (event.type == 'ESC' or (event.type == 'Z' and (event.ctrl or event.oskey))):
            return self.end(context, keep=False, why="Stylize cancelled while finishing: mesh restored")
        if event.type in {'RET', 'NUMPAD_ENTER', 'TAB', 'LEFTMOUSE', 'RIGHTMOUSE', 'Z'}:
            return {'RUNNING_MODAL'}
        return {'PASS_THROUGH'}  # navigation goes on

    def _finish_tick(self, context):
        """A tick of the full-resolution finish (live_run.start_finish); keeps the result once converged."""
        live = self.live
        outcome = live.finish_tick()
        for session, why in outcome.stopped:
            self.report({'WARNING'}, "Stylize stopped on '%s', its mesh restored: %s" % (session.name, why))
        if not live.sessions:
            self.cancel_keeping_edits(context)
            return {'CANCELLED'}
        fraction, text = live.finish_progress()
        self._progress = self._progress or ProgressReport(context, TITLE, status=False)
        self._progress.update(fraction, text)
        if live.finished:
            self.stop(context, keep=True)
            return {'FINISHED'}
        if outcome.stepped or time.monotonic() - self._panels_drawn > PANEL_SECONDS:
            self._redraw(context)
            self.show_status(context)
        return {'PASS_THROUGH'}

    def _redraw(self, context):
        """The viewports at every tick, their sidebars (steps, progress) a few times a second."""
        now = time.monotonic()
        sidebars = now - self._panels_drawn > PANEL_SECONDS
        if sidebars:
            self._panels_drawn = now
        redraw_viewports(context, sidebars=sidebars)

    def _show_busy(self, context):
        """Progress of new pins being prepared (shown, like the set-up's, after half a second)."""
        busy = self.live.busy()
        if busy is not None:
            self._progress = self._progress or ProgressReport(context, TITLE, status=False)
            self._progress.update(busy.fraction, busy.text())
        elif self._progress is not None:
            self._progress.end()
            self._progress = None

    def end(self, context, keep, why=None):
        """End the run from an event (see modal_events): keep the results or restore every mesh.
        why: reported when the run is cancelled by something other than Esc. Returns what modal() returns."""
        if keep and not self.live.preparing:
            for name in self.live.drop_gone():  # deleted since the last tick: nothing to keep
                self.report({'WARNING'}, "Stylize stopped on '%s': the object was deleted or its mesh "
                                         "replaced" % name)
            if self.live.sessions:
                if not self.live.finishing and self.live.start_finish():  # a proxy run: finish it first
                    self._progress = self._progress or ProgressReport(context, TITLE, status=False)
                    self.show_status(context)
                    return {'RUNNING_MODAL'}
                self.stop(context, keep=True)
                return {'FINISHED'}
        self.cancel_keeping_edits(context)
        if why:
            self.report({'INFO'}, why)
        return {'CANCELLED'}

    def cancel_keeping_edits(self, context):
        """Restore every mesh and end the run as Esc does: what the artist edited meanwhile (settings,
        moves, deleted objects) stays and becomes one undo step. True if that step was pushed."""
        edited = self.live.edited() or self._operators_ran(context)
        self.stop(context, keep=False)
        if edited:
            # Undo was off during the run: record what was edited meanwhile as one step
            # (the meshes are back as they were, so no cancelled shape is in it).
            bpy.ops.ed.undo_push(message=EDITS_UNDO_NAME)
        return edited

    def _operators_ran(self, context):
        """Did an operator the artist ran (a Move, a Delete...) register during the run? Each tick
        looks, because an undo empties the list before the run hears of it."""
        last = _last_registered_operator(context)
        self._operator_ran = self._operator_ran or last not in (self._operator_at_start, None)
        return self._operator_ran

    def hold_for_save(self, context):
        """Just before a file is written (runs.py): the meshes as Esc would leave them."""
        self.live.hold_for_save()

    def resume_after_save(self, context):
        """After the file was written: the run's results back, and the status bar says what was saved."""
        self.live.resume_after_save()
        self.notes["saved"] = SAVED_NOTE
        self.report({'INFO'}, SAVED_REPORT % bpy.path.basename(bpy.data.filepath))
        self.show_status(context)

    def stop(self, context, keep):
        """End the run: keep the results (callers drop deleted objects first) or restore.

        Runs once: Blender may still call cancel() after an undo or disabling the
        add-on ended the run, and removing a removed timer reads freed memory.
        """
        if self._timer is None:
            return
        live = self.live
        if not self._handlers_told:
            self._handlers_told = True
            try:
                modal_events.run_ended(self, context, keep)
            except Exception as exc:  # a feature's clean-up must not keep the meshes from being restored
                self.report({'WARNING'}, "Stylize: ending a handler failed: %s" % exc)
        if keep:  # should this raise, the run is still on and modal() cancels it
            live.keep()
            for name, value in live.redo_values(_STEPS.hard[1]).items():
                setattr(self, name, value)
        try:
            if not keep:
                live.cancel()  # restores whatever still exists, never freed data
        finally:  # even if restoring failed: leave no timer, no stale entry and undo back on
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
            runs.forget(self)
            if self._progress is not None:
                self._progress.end()
            self.show_status(context, clear=True)
            redraw_viewports(context)

    def cancel(self, context):
        # Blender cancels a modal operator when e.g. its window closes, a file loads or it quits.
        self.stop(context, keep=False)

    def show_status(self, context, clear=False):
        """Write the status bar text (event handlers call it after changing notes). The viewport's
        header keeps its menus, its mode menu being a way to Weight Paint during a run, except while a
        handler has the keys (a handle drag): then it says what they do, where the artist looks."""
        text = None if clear else self.live.status_line(self.notes)
        area = existing_area(self._area_pointer)
        if area is not None:
            keys_taken = any(isinstance(note, modal_events.KeysNote) for note in self.notes.values())
            area.header_text_set(text if keys_taken else None)
        if context.workspace is not None:
            context.workspace.status_text_set(text)

    def panel_state(self):
        return self.live.panel_state()

    @property
    def tick_ms(self):
        return list(self.live.tick_ms)

    @property
    def session(self):
        """The first object's session (the active object's, when it could be stylized)."""
        return self.live.sessions[0] if self.live.sessions else None

    @property
    def sessions(self):
        return list(self.live.sessions)


class OBJECT_OT_gauss_stylize_reset(bpy.types.Operator):
    """Put back the coordinates the mesh had when its last kept stylization started"""
    bl_idname = "object.gauss_stylize_reset"
    bl_label = "Reset"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        problem = _idle_object_problem(context)
        if problem is None and not rest_store.has_capture(context.active_object.data):
            problem = "Nothing to reset: this mesh has not been stylized"
        return poll_result(cls, problem)

    def execute(self, context):
        try:
            rest_store.restore(context.active_object)
        except SettingsError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        return {'FINISHED'}


class OBJECT_OT_gauss_replay(bpy.types.Operator):
    """Re-run this mesh's kept runs from the shape they started from, with the settings, painted weights and handle moves each had at every step"""
    bl_idname = "object.gauss_replay"
    bl_label = "Replay"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        problem = _idle_object_problem(context)
        if problem is None:
            problem = replay.problem(context.active_object)
        return poll_result(cls, problem)

    def execute(self, context):
        obj = context.active_object
        try:
            with ProgressReport(context, TITLE) as report:
                count, steps = replay.replay(obj, lambda fraction: report.update(fraction, "Replaying '%s'" % obj.name))
        except SettingsError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        self.report({'INFO'}, "Replayed %d kept run%s of '%s' (%d steps)" % (count, "s" * (count != 1), obj.name, steps))
        return {'FINISHED'}


classes = (OBJECT_OT_gauss_stylize, OBJECT_OT_gauss_stylize_reset, OBJECT_OT_gauss_replay)
