"""The objects of one live run: their set-up on a worker thread, then solver steps at every tick.

Nothing here touches the interface: the modal operator (operators.py) is the event loop, which
reports what ``finish_setup()`` and ``tick()`` return and shows what this class words for it: the
status line (``status_line()``), the sidebar box (``panel_state()``) and, once kept, the values its
redo panel repeats (``redo_values()``).

A tick gives every object at most one step, in turn, until the tick's time
budget is used; the next tick goes on with the object after the last one
stepped (round-robin), so with a short budget every object still advances
equally. An object whose settings cannot run pauses (the others go on); an
object that fails or disappears is restored and leaves the run. An object that
has converged (its last step moved it by less than its Tolerance) is not
stepped until a change of its settings, styles or pins makes its solver forget
that, then it resumes by itself.

An object above its Proxy Threshold runs on a proxy (proxy_run.py), whose steps run on a worker
thread (proxy_stepper.py): its tick takes the step the worker finished, lets the changes reach the
solver, starts the next step and writes the one taken while the next runs (_tick_on_proxy), so no
tick waits for a step and the mesh is only ever written here, on the main thread. Keeping the run then first
finishes it (``start_finish()``): a full-resolution solver is set up on a worker thread, warm-started
from the shape the proxy gave the mesh, and ticks step it until it converges (``finished``); the
operator keeps the result only then, and Esc meanwhile restores the mesh as before the run.
"""

import math
import time
from collections import deque

import bpy

from ..errors import SettingsError
from ..settings.schema import UNTIL_CONVERGED_CAP
from ..settings.settings_io import objects_to_json, to_dict
from .pin_targets import targets_json
from .progress import progress_text, settling_details, settling_fraction, settling_text
from .session import TIMINGS_KEPT, Session
from .solver_setup import BackgroundSetup, SolverSetup
from .targets import TITLE

TICK_SECONDS = 0.01  # the timer of a run in the UI (a Stylize, a bake): how often it gets a tick
TICK_BUDGET = 1.0 / 30.0  # seconds of solver steps per tick before the rest wait for the next one
CONVERGED = "Converged"  # status bar and panel: the object is not stepped until something changes
KEY_HINTS = ("Enter / Left-click: keep", "Esc / Right-click: cancel")  # what modal_events does with keys
# In Weight Paint clicks paint (modal_events.clicks lets them through) and the object holds still.
PAINT_HINTS = ("Left-drag: paint the Region's strength", "Ctrl+Tab / Back to Object Mode: stop painting, "
               "the run takes the strokes", "Enter: keep", "Esc: cancel")
PIN_HINT = "Drag a pin: move its handle"  # what handle_tool does, where a run has pins
SETUP_HINT = "Esc: cancel"
# A file saved during a run holds the meshes as they were before it (what Esc restores).
SAVED_NOTE = "Saved without this run (Enter keeps it)"
SAVED_REPORT = "Saved %s with the meshes as before Stylize: the live run goes on, and is saved once kept"
HELD_BACK = "held back by Avoid Self-Intersections at %d vertices"  # the guard, not convergence, stopped it
# Steps ran away and fell back to plain ARAP (Session.unstable, docs/robustness.md).
UNSTABLE = "unstable: lower Lambda or ADMM Iterations"
PROXY = "on a proxy of %s vertices"  # the run solves on a proxy (proxy_run.py), the mesh follows it
FINISHING = "Finishing at full resolution"  # after Enter on a proxy run, until it converges
FINISH_HINT = "Esc: cancel (the mesh as before Stylize)"


class KeysNote(str):
    """A note (run.notes) of a handler that has the keys for now, e.g. a handle being dragged: the
    header and status bar show it alone, so that no key is said to do two things."""


def held_back(session):
    """Did Avoid Self-Intersections, rather than convergence, stop ``session``'s run (Solver.held_back)?"""
    return session.held_back


class TickOutcome:
    """paused:  [(object name, why)] for objects that paused at this tick (each reason once)
    stopped: [(session, why)] for objects restored and taken out of the run
    stepped: how many objects took a step (0: nothing changed, nothing to redraw)"""

    def __init__(self):
        self.paused, self.stopped = [], []
        self.stepped = 0


class LiveRun:
    def __init__(self, planned):
        """planned: targets.Planned; their solvers are set up from now on (SolverSetup)."""
        self.planned = planned
        for plan in planned.plans:
            plan.use_proxy()
        self.setup = SolverSetup(planned.plans)
        self.finishing = False  # start_finish() began the full-resolution finish of a proxy run
        self.finish_setup_job = None  # its full-resolution solvers being set up (BackgroundSetup)
        self._finishing = []  # the sessions being finished
        self._finish_start = {}  # session -> its steps when the finish began
        self.sessions = []
        self.paused = {}     # session -> why it cannot step now
        self.next = 0        # index of the session the next tick starts with
        self.tick_ms = deque(maxlen=TIMINGS_KEPT)  # ms of the last TIMINGS_KEPT ticks that stepped
        self.held = False    # hold_for_save() showed the meshes as before the run; resume_after_save() not yet
        # session -> (Tolerance, the most it has settled since its last change at that Tolerance): the
        # last step's change rises at times (the accelerated iteration restarts); "settling" does not go back.
        self.settled = {}
        self._proxy_base = {}  # session on a proxy -> _settling_base() when its worker's step began

    @property
    def preparing(self):
        return self.setup is not None

    @property
    def converged(self):
        """The sessions a tick leaves alone because they converged (as their last sync left them)."""
        return {s for s in self.sessions if s.at_rest and s.busy is None and s not in self.paused}

    # -- set-up -------------------------------------------------------------------

    def finish_setup(self):
        """Once ``setup.done``: a Session per solver built. Returns [(object name, why)] of the skipped."""
        skipped = []
        for plan, result in zip(self.planned.plans, self.setup.results):
            try:
                if isinstance(result, Exception) or result is None:
                    raise result or SettingsError("the set-up did not finish")
                why = plan.changed()
                if why is not None:
                    raise SettingsError(why)
                self.sessions.append(Session(plan, result, background_pins=True))
            except SettingsError as exc:
                skipped.append((plan.name, str(exc)))
                self.planned.give_up(plan)
        self.setup = None
        return skipped

    # -- finishing a proxy run at full resolution ---------------------------------

    def start_finish(self):
        """After Enter: set up the full-resolution solvers of the sessions on a proxy. False (nothing
        to finish: keep at once) if none is."""
        self._finishing = [session for session in self.sessions if session.on_proxy]
        if not self._finishing:
            return False
        self.finishing = True
        for session in self._finishing:
            # Its worker's step is dropped (the mesh shows the last one written) and what changed while
            # it ran reaches the session, as the next tick would have made it reach.
            session.stop_stepping()
            if session.busy is None:
                session.sync_settings()  # a problem: the finish goes on with the settings that ran
        tasks = [session.finish_task() for session in self._finishing]
        for session in self._finishing:
            session.leave_proxy()
        self.finish_setup_job = BackgroundSetup(self._finishing[0].gauss_core, tasks)
        return True

    def finish_tick(self):
        """One tick of the finish: once the set-up is done, the sessions go on at full resolution and
        ticks step them. Returns a TickOutcome (stopped: sessions whose finish failed, restored)."""
        job = self.finish_setup_job
        if job is not None:
            if not job.done:
                return TickOutcome()
            self.finish_setup_job = None
            outcome = TickOutcome()
            for session, result in zip(self._finishing, job.results):
                try:
                    if isinstance(result, Exception) or result is None:
                        raise result or SettingsError("the full-resolution set-up did not finish")
                    session.finish_on(result)
                    self._finish_start[session] = session.steps
                    self.settled.pop(session, None)
                except SettingsError as exc:
                    outcome.stopped.append((session, str(exc)))
            for session, _why in outcome.stopped:
                self._drop(session)
                self._finishing.remove(session)
            return outcome
        return self.tick()

    @property
    def finished(self):
        """Has every finished session converged (or run UNTIL_CONVERGED_CAP full-resolution steps)?"""
        if not self.finishing or self.finish_setup_job is not None:
            return False
        return all(session.at_rest or session.steps - self._finish_start[session] >= UNTIL_CONVERGED_CAP
                   for session in self._finishing if session in self.sessions)

    def finish_progress(self):
        """(fraction, text) of the finish for the progress indicator and the status line."""
        job = self.finish_setup_job
        if job is not None:
            return job.fraction, job.text()
        sessions = [session for session in self._finishing if session in self.sessions]
        fractions = [1.0 if session.at_rest else (self.settling(session) or 0.0) for session in sessions]
        steps = max((session.steps - self._finish_start[session] for session in sessions), default=0)
        return min(fractions, default=1.0), "%s, step %d" % (FINISHING, steps)

    # -- running ------------------------------------------------------------------

    def tick(self, budget=TICK_BUDGET):
        """Sync settings and step objects in turn for up to ``budget`` seconds (at least one step); an
        object on a proxy steps on its worker instead (_tick_on_proxy)."""
        outcome = TickOutcome()
        if self.held:  # a save that failed never reached its save_post: put the results back now
            self.resume_after_save()
        start = time.perf_counter()
        count, first = len(self.sessions), self.next
        stepped = 0
        for offset in range(count):
            index = (first + offset) % count
            session = self.sessions[index]
            if not session.object_alive():
                outcome.stopped.append((session, "the object was deleted or its mesh replaced"))
                continue
            if session.busy is not None:  # re-factoring for new pins on another thread
                continue
            if session.on_proxy:  # its steps run on a worker: this tick waits for none of them
                stepped += self._tick_on_proxy(session, outcome)
                continue
            if not self._sync(session, outcome):
                continue
            if session.busy is not None:  # the sync began re-factoring for new pins: wait for it
                continue
            if session.painting:  # held still while its weights are painted; read on the way back
                continue
            if session.at_rest:  # and nothing changed since: no step, no CPU
                continue
            base = self._settling_base(session)
            try:
                session.step()
            except (SettingsError, ValueError, RuntimeError) as exc:
                outcome.stopped.append((session, str(exc)))
                continue
            self._settled_after(session, base)
            stepped += 1
            self.next = (index + 1) % count
            if time.perf_counter() - start > budget:
                break
        if stepped:
            self.tick_ms.append((time.perf_counter() - start) * 1000.0)
        outcome.stepped = stepped
        for session, _why in outcome.stopped:
            self._drop(session)
        return outcome

    def _sync(self, session, outcome):
        """Bring ``session``'s settings to its solver. False if they cannot run: it pauses, and the
        outcome says why once (not at every tick)."""
        problem = session.sync_settings()
        if problem is None:
            self.paused.pop(session, None)
            return True
        if self.paused.get(session) != problem:
            outcome.paused.append((session.name, problem))
        self.paused[session] = problem
        return False

    def _settling_base(self, session):
        """(Tolerance, how far ``session`` had settled) before its next step: 0 after a change."""
        tolerance = session.applied["tolerance"]
        before, settled = self.settled.get(session, (None, 0.0))
        if before != tolerance or not math.isfinite(session.reldv):  # inf: a setting changed
            settled = 0.0
        return tolerance, settled

    def _settled_after(self, session, base):
        """Book how far ``session`` settled in the step just taken, from _settling_base()'s ``base``."""
        tolerance, settled = base
        self.settled[session] = (tolerance, max(settled, settling_fraction(session.reldv, tolerance) or 0.0))

    def _tick_on_proxy(self, session, outcome):
        """A tick of a session on a proxy, whose steps run on a worker thread (proxy_stepper.py): while a
        step runs, nothing (the changes wait for it); once it is done, take it (transferred to the whole
        mesh on the worker), let the changes reach the solver, start the next step, and write the one
        taken into the mesh while the next runs. So the
        changes reach the solver between the same steps, in the same order, as on the main thread, and
        the main thread never waits for a step. Returns 1 if it wrote a new state, else 0."""
        if session.stepping:
            return 0
        taken = session.step_done
        if taken:
            try:
                session.take_step()
            except (SettingsError, ValueError, RuntimeError) as exc:
                outcome.stopped.append((session, str(exc)))
                return 0
            self._settled_after(session, self._proxy_base.pop(session))
        # Not while new pins are prepared, weights painted, or at rest (as tick() steps).
        if self._sync(session, outcome) and session.busy is None and not session.painting and not session.at_rest:
            self._proxy_base[session] = self._settling_base(session)
            session.start_step()
        if not taken or session.painting:  # held still while painted, as tick() holds it: the step taken
            return 0                        # began before, and shows once the strokes are read
        try:
            session.write_taken()
        except (SettingsError, ValueError, RuntimeError) as exc:
            outcome.stopped.append((session, str(exc)))
            return 0
        return 1

    def _drop(self, session):
        """Restore ``session``'s object as far as it exists and take it out of the run."""
        self.sessions.remove(session)
        self.paused.pop(session, None)
        self.settled.pop(session, None)
        self._proxy_base.pop(session, None)
        self.next = 0
        session.cancel()

    def drop_gone(self):
        """Take the objects deleted since the last tick out (before keeping). Returns their names."""
        gone = [session for session in self.sessions if not session.object_alive()]
        for session in gone:
            self._drop(session)
        return [session.name for session in gone]

    def edited(self):
        """Do the run's objects have settings other than those they started with (or a default
        style the run added and keeps)? Asked before a cancel."""
        if self.setup is None and self.planned.slot_added:
            return True
        for plan in self.planned.plans:
            try:
                if to_dict(plan.obj.gauss_stylization) != plan.applied:
                    return True
            except ReferenceError:  # deleted during the run: an edit too
                return True
        return False

    # -- saving -------------------------------------------------------------------

    def hold_for_save(self):
        """Show every mesh as cancel() would leave it while the file is written: a run is not the
        artist's until it is kept, so a file saved meanwhile must not hold a half-stylized mesh."""
        for session in self.sessions:
            if session.object_alive():
                session.hold()
        self.held = True

    def resume_after_save(self):
        """Put the run's results back after the file was written (the run goes on)."""
        self.held = False
        for session in self.sessions:
            if session.object_alive():
                session.resume()

    # -- ending -------------------------------------------------------------------

    def keep(self):
        for session in self.sessions:
            session.keep()

    def cancel(self):
        """Restore every object (a set-up still running is stopped: nothing was changed yet)."""
        if self.finish_setup_job is not None:
            self.finish_setup_job.cancel()
            self.finish_setup_job = None
        if self.setup is not None:
            self.setup.cancel()
            self.setup = None
            self.planned.undo_added_slots()
            return
        failure = None
        for session in self.sessions:  # restore as many as possible even if one fails
            try:
                session.cancel()
            except Exception as exc:  # noqa: BLE001 (re-raised below, after the others)
                failure = failure or exc
        if failure is not None:
            raise failure

    # -- what it shows ------------------------------------------------------------

    @property
    def steps(self):
        """Steps of the first object (what the redo panel repeats)."""
        return self.sessions[0].steps if self.sessions else 0

    def settling(self, session):
        """The most ``session`` has settled since its last change (settling_fraction), or None before
        its first step and after a change it has not stepped since."""
        if session not in self.settled or not math.isfinite(session.reldv):
            return None
        return self.settled[session][1]

    def status_text(self):
        """One line for the header and the status bar (without the key hints)."""
        if self.preparing:
            return TITLE + ": " + progress_text(self.setup.text(), self.setup.fraction)
        if self.finishing:
            fraction, text = self.finish_progress()
            return TITLE + ": " + progress_text(text, fraction)
        sessions = self.sessions
        if not sessions:
            return TITLE
        held_back_ones = [s for s in sessions if held_back(s)]
        converged = self.converged - set(held_back_ones)
        if len(sessions) == 1:
            session = sessions[0]
            text = TITLE + ": step %d" % session.steps
            fraction = self.settling(session)
            if held_back_ones:
                text += "  |  " + HELD_BACK % session.held_vertices
            elif converged:
                text += "  |  " + CONVERGED
            elif fraction is not None and not session.unstable:  # unstable: it does not settle
                text += "  |  " + settling_text(fraction)
            if not converged and not held_back_ones and session.step_ms and self.tick_ms:
                text += "  |  %.1f ms/step, %.1f ms/tick" % (session.step_ms[-1], self.tick_ms[-1])
        else:
            steps = [session.steps for session in sessions]
            text = TITLE + ": %d objects, step %s" % (
                len(sessions), min(steps) if min(steps) == max(steps) else "%d-%d" % (min(steps), max(steps)))
            if len(converged) == len(sessions):
                text += "  |  " + CONVERGED + " (all)"
            elif converged:
                text += "  |  %s: %s" % (CONVERGED, ", ".join(sorted("'%s'" % s.name for s in converged)))
            for session in held_back_ones:
                text += "  |  '%s' %s" % (session.name, HELD_BACK % session.held_vertices)
            if self.tick_ms and len(converged) + len(held_back_ones) < len(sessions):
                text += "  |  %.1f ms/tick" % self.tick_ms[-1]
        for session in sessions:
            if session.on_proxy:
                text += "  |  " + ("'%s' " % session.name if len(sessions) > 1 else "") + PROXY % "{:,}".format(
                    session.proxy.num_vertices)
        for session, why in self.paused.items():
            text += "  |  " + (("'%s' paused: " % session.name) if len(sessions) > 1 else "paused: ") + why
        held = sum(session.held_vertices for session in sessions if session not in held_back_ones)
        if held:
            text += "  |  %d vertices held back from passing through" % held
        for session in sessions:
            if session.unstable:
                text += "  |  " + ("'%s' " % session.name if len(sessions) > 1 else "") + UNSTABLE
        for session in sessions:
            busy = session.busy
            if busy is not None:
                text += "  |  " + ("'%s': " % session.name if len(sessions) > 1 else "") + progress_text(
                    busy.text(), busy.fraction)
        return text

    def busy(self):
        """A set-up the run waits for besides the first one (new pins being prepared), or None."""
        return next((session.busy for session in self.sessions if session.busy is not None), None)

    def panel_title(self):
        """The sidebar box's first row: "Preparing... 40%", "Stylizing live", "Converged" or "Held back"."""
        if self.preparing:
            return progress_text("Preparing", self.setup.fraction)
        if self.finishing:
            fraction, _text = self.finish_progress()
            return progress_text("Finishing", fraction)
        stopped = [s for s in self.sessions if s in self.converged or held_back(s)]
        if self.sessions and len(stopped) == len(self.sessions):
            return "Held back" if any(held_back(s) for s in stopped) else CONVERGED
        return "Stylizing live"

    def panel_lines(self):
        """(text, icon) or (text, icon, tooltip) rows for the sidebar under the title: each object and
        how far it is."""
        if self.preparing:
            return [(plan.name, 'MESH_DATA') for plan in self.planned.plans]
        lines = []
        for session in self.sessions:
            busy = session.busy
            if busy is not None:
                lines.append(("%s: %s" % (session.name, progress_text(busy.text(), busy.fraction)), 'TIME'))
            elif session in self.paused:
                lines.append(("%s: paused" % session.name, 'PAUSE'))
            elif held_back(session):
                lines.append(("%s: %s, step %d" % (session.name, HELD_BACK % session.held_vertices,
                                                   session.steps), 'ERROR'))
            elif session in self.converged:
                lines.append(("%s: converged, step %d" % (session.name, session.steps), 'CHECKMARK'))
            else:
                lines.append(("%s: step %d" % (session.name, session.steps), 'MESH_DATA'))
                if session.on_proxy:
                    lines.append((PROXY % "{:,}".format(session.proxy.num_vertices), 'MOD_DECIM'))
                fraction = self.settling(session)
                if session.unstable:
                    lines.append((UNSTABLE, 'ERROR'))
                elif fraction is not None:
                    lines.append((settling_text(fraction), 'BLANK1',
                                  settling_details(session.reldv, session.applied["tolerance"])))
        return lines

    # -- what the Stylize operator shows of the run, and what its redo panel repeats --------------

    def key_hints(self):
        """The keys that act on the run now; the pin hint only where an object has a Pin Group."""
        if self.preparing:
            return (SETUP_HINT,)
        if self.finishing:
            return (FINISH_HINT,)
        if bpy.context.mode == 'PAINT_WEIGHT':
            return PAINT_HINTS
        pinned = any(session.object_alive() and session.obj.gauss_stylization.pin_group
                     for session in self.sessions)
        return KEY_HINTS + (PIN_HINT,) if pinned else KEY_HINTS

    def status_line(self, notes):
        """The header and status bar: status_text(), the notes ({name: text} of event handlers), the keys;
        or what a handler that has the keys for now says (a KeysNote: a drag's Esc is not the run's)."""
        keys_taken = [note for note in notes.values() if isinstance(note, KeysNote)]
        if keys_taken:
            return TITLE + ": " + keys_taken[-1]
        notes = "".join("  |  " + note for note in notes.values() if note)
        return self.status_text() + notes + "  |  " + "  |  ".join(self.key_hints())

    def panel_state(self):
        """(title, [(text, icon)], key hints) for the sidebar's box while the run goes on (ui.py)."""
        return self.panel_title(), self.panel_lines(), self.key_hints()

    def redo_values(self, max_steps):
        """{operator property: value} of a kept run, so that the redo panel repeats it: its steps (at
        most max_steps), the settings it ended with and where it left dragged pins."""
        return {"iterations": min(self.steps, max_steps),
                "settings_json": objects_to_json([session.obj for session in self.sessions]),
                "pin_targets": targets_json(self.sessions)}
