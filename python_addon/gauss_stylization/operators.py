"""Operators: Stylize (live modal run or scripted steps) and Reset."""

import time

import bpy
from bpy.props import StringProperty

from . import handle_tool, handles, rest_store, runs, schema, settings_io, sphere_editing
from .errors import NativeModuleError, SettingsError
from .session import Session, ensure_style_slot
from .validation import object_problem, poll_result
from .viewport import existing_area, over_viewport, redraw_viewports

TICK_SECONDS = 0.01
KEY_HINTS = ("Enter / Left-click: keep", "Esc / Right-click: cancel",  # what modal() does with keys
             "Drag a pin: move its handle")
HINT = "  |  ".join(KEY_HINTS)
_STEPS = schema.field(schema.OBJECT, "iterations")


def stylize_problem(context):
    problem = object_problem(context)
    if problem is None and runs.is_running(context.active_object):
        problem = "Stylization is already running on this object"
    return problem


def start_session(operator, context):
    """Validate and set up a run on the active object; report and return None on failure."""
    obj = context.active_object
    others = [o for o in context.selected_objects if o != obj]
    if others:
        operator.report({'INFO'}, "Stylizing only the active object '%s' (%d other objects selected)"
                        % (obj.name, len(others)))
    added = ensure_style_slot(obj.gauss_stylization)
    try:
        session = Session(obj)
    except (SettingsError, NativeModuleError) as exc:
        if added:  # a failed start changes nothing, settings included
            obj.gauss_stylization.styles.remove(0)
        operator.report({'ERROR'}, str(exc))
        return None
    if added:
        operator.report({'INFO'}, "No style slot yet: added a %s style" % obj.gauss_stylization.styles[0].name)
    return session


class OBJECT_OT_gauss_stylize(bpy.types.Operator):
    """Stylize the active mesh live: one solver step per tick, settings apply at once.
    Enter/left-click keeps the result, Esc/right-click restores the mesh"""
    bl_idname = "object.gauss_stylize"
    bl_label = "Stylize"
    bl_options = {'REGISTER', 'UNDO'}

    # The range and default of the object's Script Steps, which a script run defaults to.
    iterations: _STEPS.prop({}, label="Iterations",
                            tooltip="Solver steps (scripts: defaults to the object's Script Steps setting)")
    # Settings a kept live run ended with, so the redo panel repeats that run (JSON, see settings_io).
    settings_json: StringProperty(options={'HIDDEN', 'SKIP_SAVE'})
    # Where a kept live run left dragged pins, so the redo panel repeats it; scripts may set it too:
    # '{"object name": [[x, y, z], ...]}', one target per Pin Group vertex (handles.targets_json).
    pin_targets: StringProperty(name="Pin Targets", options={'HIDDEN', 'SKIP_SAVE'},
                                description="New positions of the pinned vertices, JSON by object name")

    @classmethod
    def poll(cls, context):
        return poll_result(cls, stylize_problem(context))

    # -- scripted / background / redo: run synchronously ------------------------

    def execute(self, context):
        settings = context.active_object.gauss_stylization
        if self.settings_json:
            try:
                settings_io.apply_json(settings, self.settings_json)
            except (ValueError, KeyError, TypeError) as exc:
                self.report({'ERROR'}, "Unreadable settings_json (%s): %s" % (type(exc).__name__, exc))
                return {'CANCELLED'}
        if not self.properties.is_property_set("iterations"):
            self.iterations = settings.iterations
        session = start_session(self, context)
        if session is None:
            return {'CANCELLED'}
        try:
            if self.pin_targets:
                handles.apply_targets_json([session], self.pin_targets)
            if self.iterations:
                session.step(self.iterations)
        except SettingsError as exc:
            session.cancel()
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        except (ValueError, RuntimeError) as exc:
            session.cancel()
            self.report({'ERROR'}, "The solver failed: %s" % exc)
            return {'CANCELLED'}
        session.keep()
        return {'FINISHED'}

    # -- interactive: modal on a timer -------------------------------------------

    def invoke(self, context, event):
        if context.window is None or bpy.app.background:
            return self.execute(context)  # no window to run live in
        session = start_session(self, context)
        if session is None:
            return {'CANCELLED'}
        self._session = session
        # The area's address only, never a Python reference to it: see viewport.existing_area.
        self._area_pointer = context.area.as_pointer() if context.area else None
        self._message = "starting"
        self._tick_ms = []
        self._handles = handle_tool.HandleTool()
        window_manager = context.window_manager
        self._timer = window_manager.event_timer_add(TICK_SECONDS, window=context.window)
        window_manager.modal_handler_add(self)
        runs.start(context.active_object, self)
        self._show_status(context)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if self._timer is None:
            # Already ended outside an event (undo handler, add-on disabled); the
            # handler is still there until it returns, and the event is not ours.
            return {'CANCELLED', 'PASS_THROUGH'}
        try:
            return self._handle_event(context, event)
        except Exception as exc:  # never leave a half-done run or a dangling timer behind
            self.stop(context, keep=False)
            self.report({'ERROR'}, "Stylize stopped, mesh restored: %s" % exc)
            return {'CANCELLED'}

    def _handle_event(self, context, event):
        if event.type == 'TIMER':
            if not self._tick(context):
                return {'CANCELLED'}
            return {'PASS_THROUGH'}  # other operators may own this timer event
        taken = self._handles.event(context, event, [self._session])  # pin handles: press, drag, drop
        if taken is not None:
            self._show_status(context)
            return taken
        if event.value != 'PRESS':
            return {'PASS_THROUGH'}
        if sphere_editing.claims(context, event):
            return {'PASS_THROUGH'}  # a press on the Gauss sphere edits it (sphere_editing)
        if event.type == 'ESC' or (event.type == 'RIGHTMOUSE' and over_viewport(context, event)):
            self.stop(context, keep=False)
            return {'CANCELLED'}
        if event.type in {'RET', 'NUMPAD_ENTER'} or (
                event.type == 'LEFTMOUSE' and over_viewport(context, event)):
            if not self._session.object_alive():  # deleted since the last tick: nothing to keep
                self._stop_object_gone(context)
                return {'CANCELLED'}
            self.stop(context, keep=True)
            return {'FINISHED'}
        if event.type == 'TAB' or (event.type == 'Z' and (event.ctrl or event.oskey)):
            return {'RUNNING_MODAL'}  # no mode switch or undo under a live run
        return {'PASS_THROUGH'}  # navigation and the sidebar keep working

    def _tick(self, context):
        """One step with the current settings. False if the run had to stop."""
        session = self._session
        if not session.object_alive():
            self._stop_object_gone(context)
            return False
        if context.mode != 'OBJECT':
            # Edit Mode would overwrite a restore on exit, so keep what is there
            # and let Reset (which has the start coordinates) take it back.
            self.stop(context, keep=True)
            self.report({'WARNING'}, "Stylize stopped: the object left Object Mode. "
                                     "Use Reset in Object Mode to get the original back")
            return False
        start = time.perf_counter()
        problem = session.sync_settings()
        if problem is None:
            session.step()
            redraw_viewports(context)
            self._tick_ms.append((time.perf_counter() - start) * 1000.0)
        self._message = "paused: " + problem if problem else None
        self._show_status(context)
        return True

    def stop(self, context, keep):
        """End the run: keep the result (callers check the object is alive) or restore.

        Runs once: Blender may still call cancel() after an undo or disabling the
        add-on ended the run, and removing a removed timer reads freed memory.
        """
        if self._timer is None:
            return
        self._handles.drop()
        session = self._session
        if keep:  # should this raise, the run is still on and modal() cancels it
            session.keep()
            self.iterations = session.steps
            self.settings_json = settings_io.to_json(session.obj.gauss_stylization)
            self.pin_targets = handles.targets_json([session])
        try:
            if not keep:
                session.cancel()  # restores whatever still exists, never freed data
        finally:  # even if restoring failed: leave no timer and no stale entry behind
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
            runs.forget(self)
            self._show_status(context, clear=True)
            redraw_viewports(context)

    def _stop_object_gone(self, context):
        self.stop(context, keep=False)
        self.report({'WARNING'}, "Stylize stopped: the object was deleted or its mesh replaced")

    def cancel(self, context):
        # Blender cancels a modal operator when e.g. its window closes or a file loads.
        self.stop(context, keep=False)

    def _show_status(self, context, clear=False):
        text = None if clear else self._status_text()
        area = existing_area(self._area_pointer)
        if area is not None:
            area.header_text_set(text)
        if context.workspace is not None:
            context.workspace.status_text_set(text)

    def _status_text(self):
        session = self._session
        text = "Gauss Stylize: step %d" % session.steps
        if session.step_ms:
            text += "  |  %.1f ms/step, %.1f ms/tick" % (session.step_ms[-1], self._tick_ms[-1])
        if self._message:
            text += "  |  " + self._message
        dragging = self._handles.hint()
        if dragging:
            return text + "  |  " + dragging
        return text + "  |  " + HINT

    @property
    def tick_ms(self):
        return list(self._tick_ms)

    @property
    def session(self):
        return self._session


class OBJECT_OT_gauss_stylize_reset(bpy.types.Operator):
    """Put back the coordinates the mesh had when its last kept stylization started"""
    bl_idname = "object.gauss_stylize_reset"
    bl_label = "Reset"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        problem = stylize_problem(context)
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


classes = (OBJECT_OT_gauss_stylize, OBJECT_OT_gauss_stylize_reset)
