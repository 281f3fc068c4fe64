"""Operators that bake to a point cache: Bake Animation and Bake Progress (bake.py).

From a script or in background mode they run synchronously and print a progress
line at least every 10%; from the UI they run in the background of Blender's
event loop (a timer, frames for up to TICK_BUDGET seconds per tick) with the
progress indicator, and Esc cancels, leaving no file and no modifier behind.
Progress goes through the add-on's shared ProgressReport (progress.py). A bake
registers as a run (runs.py), so Stylize and Reset wait for it and undo cancels
it first.
"""

import time

import bpy
from bpy.props import IntProperty, StringProperty

from ..errors import NativeModuleError, SettingsError
from ..run import runs
from ..run.live_run import TICK_SECONDS  # the live run's timer: the same responsiveness
from ..run.progress import ProgressReport
from ..run.session import ensure_style_slot
from ..run.targets import stylize_problem
from ..settings import schema
from ..settings.validation import object_problem, poll_result
from ..view.viewport import redraw_sidebars
from . import bake

TICK_BUDGET = 0.1  # seconds of baking per tick (at least one frame), so the UI stays responsive
# The sidebar gets the bake's box at its start, and Blender slides the panels below it into place over
# 0.3 s, a step per redraw, from the end of the box's first drawing (where it lays the panels out);
# until then the sub-panels' headers are drawn over the panel, and a frame baked meanwhile (a second
# or more on a big mesh) held them there. The box's layout code runs before that end, and on a slow
# machine the drawing takes a good part of the 0.3 s, so the slide is timed from the box's second
# drawing, which begins after the first has ended: the first frame waits for a drawing of the box this
# long after that one (the panels are in place then), or, where the box is not shown (the sidebar
# closed, another tab), for BOX_WAIT_LIMIT.
PANELS_SETTLE = 0.35
BOX_WAIT_LIMIT = 1.0
SETTLE_WAIT_LIMIT = 10.0  # a box drawn once, then hidden: the bake goes on without waiting for the panels
PANEL_SECONDS = 0.25  # how often the sidebar's box is redrawn with the frame count
FRAME_LIMIT = schema.MAX_FRAME
_STEPS = schema.field(schema.OBJECT, "iterations")

_FILEPATH_TOOLTIP = ("The .pc2 file to write (relative paths start with // and need a saved .blend); "
                     "empty: the object's Cache File (Bake panel)")


def _frame_prop(name, tooltip, default=1):
    return IntProperty(name=name, description=tooltip, default=default, min=-FRAME_LIMIT, max=FRAME_LIMIT)


_START_ERRORS = (SettingsError, NativeModuleError, OSError, ValueError)


class _BakeOperator:
    """Runs ``self.make_bake(context)`` (a bake.AnimationBake / ProgressBake) to its end.
    A bake acts on the active object alone."""

    # One undo step takes the modifier away again (the file stays); the redo panel re-bakes.
    bl_options = {'REGISTER', 'UNDO'}
    sessions = ()  # runs.py asks every run for its live Stylize sessions: a bake has none

    @classmethod
    def poll(cls, context):
        return poll_result(cls, object_problem(context) or stylize_problem(context))

    def _start(self, context):
        """The bake set up, with a default style slot added first if the object has none (taken
        back if the set-up fails: a failed start changes nothing); None if it failed (reported)."""
        obj = context.active_object
        self._job, self._obj_name = None, obj.name
        added = ensure_style_slot(obj.gauss_stylization)
        try:
            self._job = self.make_bake(context)
        except _START_ERRORS as exc:
            if added:
                obj.gauss_stylization.styles.remove(0)
            self.report({'ERROR'}, str(exc))
            return None
        if added:
            self.report({'INFO'}, "No style slot yet: added a %s style" % obj.gauss_stylization.styles[0].name)
        return self._job

    def panel_state(self):
        """(title, [(text, icon)], key hints) for the sidebar's box while the bake runs (ui.py)."""
        now = time.monotonic()
        self._box_drawings += 1
        if self._box_drawings == 2:
            self._box_drawn = now
        elif self._box_drawn is not None and now >= self._box_drawn + PANELS_SETTLE:
            self._panels_settled = True
        return ("Baking to a point cache", [("%s: %s" % (self._obj_name, self._progress_text()), 'FILE_CACHE')],
                ("Esc: cancel (nothing is written)",))

    def _progress_text(self):
        return "frame %d of %d" % (self._job.done, self._job.total)

    def _update(self, report):
        report.update(self._job.done / self._job.total, self._progress_text())

    def _advance(self):
        """One frame; on failure cancel and report. False once the bake ended either way."""
        try:
            self._job.advance()
        except (SettingsError, OSError, ValueError, RuntimeError, ReferenceError) as exc:
            self._job.cancel()
            self.report({'ERROR'}, "Bake of '%s' cancelled: %s" % (self._obj_name, exc))
            return False
        return True

    def _finish(self):
        try:
            self._job.finish()
        except (OSError, ValueError, RuntimeError, ReferenceError) as exc:
            self._job.cancel()
            self.report({'ERROR'}, "Bake of '%s' could not be saved: %s" % (self._obj_name, exc))
            return {'CANCELLED'}
        self.report({'INFO'}, "Baked %d frames of '%s' to %s" % (self._job.total, self._obj_name, self._job.path))
        return {'FINISHED'}

    def _title(self):
        """What the progress indicator, status bar and printed lines call this bake."""
        return "Gauss %s '%s'" % (self.bl_label, self._obj_name)

    # -- scripts and background mode: synchronous --------------------------------------

    def execute(self, context):
        if self._start(context) is None:
            return {'CANCELLED'}
        with ProgressReport(context, self._title()) as report:
            self._update(report)
            while not self._job.finished:
                if not self._advance():
                    return {'CANCELLED'}
                self._update(report)
        return self._finish()

    # -- from the UI: modal on a timer ------------------------------------------------

    def invoke(self, context, event):
        if context.window is None or bpy.app.background:
            return self.execute(context)
        self.fill_defaults(context)
        if self._start(context) is None:
            return {'CANCELLED'}
        self._progress = ProgressReport(context, self._title())
        self._update(self._progress)
        self._timer = context.window_manager.event_timer_add(TICK_SECONDS, window=context.window)
        self._started = self._next_tick = time.monotonic()
        self._panel_drawn = 0.0
        self._box_drawings, self._box_drawn, self._panels_settled = 0, None, False  # see PANELS_SETTLE
        context.window_manager.modal_handler_add(self)
        runs.start([self._job.obj], self)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if self._timer is None:  # ended outside an event (undo, add-on disabled)
            return {'CANCELLED', 'PASS_THROUGH'}
        try:
            return self._handle_event(context, event)
        except Exception as exc:  # never leave a half-written file, a timer or a stale run behind
            self.stop(context)
            self.report({'ERROR'}, "Bake of '%s' cancelled: %s" % (self._obj_name, exc))
            return {'CANCELLED'}

    def _handle_event(self, context, event):
        if event.type == 'ESC' and event.value == 'PRESS':
            self.stop(context, keep=False)
            self.report({'WARNING'}, "Bake of '%s' cancelled; nothing was written" % self._obj_name)
            return {'CANCELLED'}
        # A modal operator sees every timer's events; only as often as its own timer runs does the
        # bake take a tick, so that the events of others (the panels' animation) pass between its ticks.
        if event.type != 'TIMER' or time.monotonic() < self._next_tick:
            return {'PASS_THROUGH'}
        if not self._panels_in_place(context):
            return {'PASS_THROUGH'}
        deadline = time.perf_counter() + TICK_BUDGET
        while not self._job.finished:
            if not self._advance():
                self._end(context)
                return {'CANCELLED'}
            if time.perf_counter() > deadline:
                break
        self._update(self._progress)
        self._next_tick = time.monotonic() + TICK_SECONDS
        if self._next_tick > self._panel_drawn + PANEL_SECONDS:  # the box's "frame N of M"
            self._panel_drawn = self._next_tick
            redraw_sidebars(context)
        if not self._job.finished:
            return {'PASS_THROUGH'}
        self._end(context)
        return self._finish()

    def _panels_in_place(self, context):
        """May the bake take its frames, the sidebar's panels being in place (PANELS_SETTLE)?"""
        waited = time.monotonic() - self._started
        if self._panels_settled or waited > SETTLE_WAIT_LIMIT or (self._box_drawings == 0 and waited > BOX_WAIT_LIMIT):
            self._panels_settled = True
            return True
        redraw_sidebars(context)  # the slide goes on at each redraw
        return False

    def stop(self, context, keep=False):
        """Cancel (runs.stop_all calls this on undo and when the add-on is disabled)."""
        if self._timer is None:
            return
        self._job.cancel()
        self._end(context)

    def cancel(self, context):
        self.stop(context)

    def cancel_keeping_edits(self, context):
        """Esc's ending (runs.py, on undo): a bake leaves no edits of its own to keep."""
        self.stop(context)
        return False

    def hold_for_save(self, context):
        """Just before a file is written (runs.py): the scene as before the bake."""
        self._job.hold()

    def resume_after_save(self, context):
        self._job.resume()
        self.report({'INFO'}, "Saved %s as before the bake (frame, cache modifier): the bake goes on"
                    % bpy.path.basename(bpy.data.filepath))

    def _end(self, context):
        context.window_manager.event_timer_remove(self._timer)
        self._timer = None
        self._progress.end()
        runs.forget(self)

    def fill_defaults(self, context):
        """Values an artist would expect where the caller gave none (subclasses)."""


def bake_range(scene, settings):
    """(first, last) frame Bake Animation bakes by default: the scene's range or the object's own."""
    if settings.bake_scene_range:
        return scene.frame_start, scene.frame_end
    return settings.bake_frame_start, settings.bake_frame_end


class OBJECT_OT_gauss_bake_animation(_BakeOperator, bpy.types.Operator):
    """Stylize every frame of the animation (the mesh as evaluated: modifiers, armature, shape keys) into a
    point cache, played back by a Mesh Cache modifier added at the end of the stack"""
    bl_idname = "object.gauss_bake_animation"
    bl_label = "Bake Animation"

    frame_start: _frame_prop("Start Frame", "First frame to bake (default: the scene's start)")
    frame_end: _frame_prop("End Frame", "Last frame to bake (default: the scene's end)")
    filepath: StringProperty(name="File Path", description=_FILEPATH_TOOLTIP, subtype='FILE_PATH')
    warm_start: schema.field(schema.OBJECT, "bake_warm_start").prop({})  # unset: the object's setting

    def fill_defaults(self, context):
        """What the caller did not give comes from the Bake panel's settings."""
        settings = context.active_object.gauss_stylization
        start, end = bake_range(context.scene, settings)
        given = self.properties.is_property_set
        if not given("frame_start"):
            self.frame_start = start
        if not given("frame_end"):
            self.frame_end = end
        if not given("warm_start"):
            self.warm_start = settings.bake_warm_start
        if not given("filepath"):
            self.filepath = settings.bake_filepath

    def make_bake(self, context):
        self.fill_defaults(context)
        return bake.AnimationBake(context, context.active_object, self.frame_start, self.frame_end,
                                  self.filepath, self.warm_start)


class OBJECT_OT_gauss_bake_progress(_BakeOperator, bpy.types.Operator):
    """Record the stylization itself as an animation (frame k: the mesh after k x Steps per Frame steps) into
    a point cache, played back by a Mesh Cache modifier"""
    bl_idname = "object.gauss_bake_progress"
    bl_label = "Bake Progress"

    steps: _STEPS.prop({}, label="Steps", tooltip="Solver steps in all (a multiple of Steps per Frame)")
    steps_per_frame: IntProperty(name="Steps per Frame", description="Solver steps between two frames",
                                 default=1, min=1, max=_STEPS.hard[1])
    frame_start: _frame_prop("Start Frame", "Frame that shows the unstylized mesh (step 0)")
    filepath: StringProperty(name="File Path", description=_FILEPATH_TOOLTIP, subtype='FILE_PATH')

    def fill_defaults(self, context):
        if not self.properties.is_property_set("filepath"):
            self.filepath = context.active_object.gauss_stylization.bake_filepath

    def make_bake(self, context):
        self.fill_defaults(context)
        return bake.ProgressBake(context, context.active_object, self.steps, self.steps_per_frame,
                                 self.frame_start, self.filepath)


classes = (OBJECT_OT_gauss_bake_animation, OBJECT_OT_gauss_bake_progress)
