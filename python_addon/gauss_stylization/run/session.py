"""One stylization run of one object: what it reads, its solver, buffers and output target.

A run is set up in two parts. ``Plan(obj)`` reads and checks everything it
needs from Blender on the main thread (what it stylizes comes from source.py:
the base mesh, or with Use Modifiers the evaluated one); a bad setting or mesh raises
SettingsError there, before anything expensive happens. ``Plan.build_solver()``
then sets up the solver from those arrays alone (no Blender data), so
solver_setup.py may run it on another thread while Blender stays responsive.
``Session(plan, solver)`` finishes on the main thread and makes the first change
to the object. ``Session(obj)`` does all three at once (scripts, benchmarks).

Used by the live run (one ``step()`` per timer tick), by the scripted operator
(``step(n)``) and by the tick benchmark. Nothing here touches the UI. A failed
start leaves the object as it was, except that settings an earlier version wrote
are brought up to date first (settings/versioning.py), which changes no result.
"""

import time
from collections import deque

import numpy as np

from .. import native
from ..errors import SettingsError
from ..mesh import follow_store, mesh_io, output, recipe_store, rest_store, source as sources
from ..settings import paint_curve, schema, styles
from ..settings.fields import Live, changes
from ..settings.settings_io import add_slot, apply_dict, to_dict
from ..settings.validation import check_coordinates, check_object, check_pins, check_settings
from ..settings.versioning import bring_stamped_up_to_date
from .proxy_run import ProxyMap, proxy_size
from .proxy_stepper import ProxyStepper
from .solver_setup import PinsSetup

# A result outside the rest mesh's coordinate range widened by this many mesh sizes is treated
# as a blow-up: the solver keeps outputs within a few sizes, so this only catches a defect.
MAX_EXTENT = 100.0

# Step (and live tick) timings are kept for the status bar (the last one) and the medians tests and
# benchmarks report, not for the whole run: a live run ticks up to 100 times a second, so an hour
# would keep ~360,000. The last 1000 are 10 s or more of a live run and more than any benchmark
# takes (measure_tick.py: 60 ticks by default), so its medians still cover every step it measured.
TIMINGS_KEPT = 1000

# A run is called unstable while a step of the last this many ran away (Session.unstable): long
# enough that the word does not flicker, short enough that it goes once a lower Lambda settles it.
UNSTABLE_STEPS = 30


def ensure_style_slot(settings):
    """An artist must be able to press Stylize right away: add a slot of the default preset
    if there is none. True if one was added."""
    if len(settings.styles) == 0:
        add_slot(settings, {"preset": schema.DEFAULT_PRESET})
        settings.active_style_index = 0
        return True
    return False


def _solver_error(exc):
    return SettingsError("The solver cannot handle this mesh or setting: %s" % exc)


class Plan:
    """Everything a run of ``obj`` needs from Blender, read and checked (main thread).

    source:  what is stylized (source.Source; default: read from ``obj`` by its Use Modifiers)
    arrays:  its mesh_io.MeshArrays (coordinates, loop triangles, corners)
    weights: {vertex group name: (#V,) float32}, read once
    applied: the settings (settings_io.to_dict) the solver is built with
    pins, styles, regions: the solver's inputs derived from them (regions: the face and vertex
             weights of Solver.set_face_weights)
    target:  output target (default: ``obj``'s Output, output.make_target), snapshot taken,
             nothing written yet

    A plan holds the source's evaluated mesh copy until the Session made from it has prepared
    its target (New Object output adopts it); a plan that gets no Session is ``release()``d.
    """

    def __init__(self, obj, source=None, target=None, weights=None):
        """weights: {group: (#V,) float32} that replace the object's own (a replayed run's, replay.py)."""
        self.obj = obj
        self._weights = weights
        self.name = obj.name  # for messages, also once the object is gone
        self.mesh = obj.data
        self.gauss_core = native.core()
        check_object(obj)
        settings = obj.gauss_stylization
        bring_stamped_up_to_date(settings)  # an object appended from an older version's file
        self.source = source if source is not None else sources.read(obj, settings.use_modifiers)
        try:
            self._read(obj, settings, target)
        except BaseException:
            self.release()
            raise

    def _read(self, obj, settings, target):
        self.arrays = self.source.arrays
        check_coordinates(obj, self.arrays.coords)
        # The base mesh as it is now, to notice an edit while the solver is set up (changed()).
        self.base_coords = self.arrays.coords
        if self.source.evaluated:
            self.base_coords = np.empty((len(self.mesh.vertices), 3), np.float32)
            mesh_io.read_base_coords(self.mesh, self.base_coords)
        self.weights = dict(self.source.weights, **self._weights) if self._weights else self.source.weights
        check_settings(obj, settings, self.weights)
        # The settings the solver runs with; a tick compares them with the panel's to find
        # what changed, and each change does what its field's Live says (schema.py).
        self.applied = to_dict(settings)
        self.pins = styles.pinned_vertices(self.weights, settings.pin_group)
        check_pins(obj, self.pins, self.arrays.triangles)
        try:
            self.styles = styles.make_styles(self.gauss_core, settings.styles)
        except (ValueError, TypeError) as exc:
            raise _solver_error(exc) from exc
        self.regions = self.regions_for(settings)
        self.solver_options = {field.name: field.read(settings) for field in schema.SOLVER_SETTERS}
        self.target = target or output.make_target(obj, self.source)
        self.proxy_target = None  # a live run's proxy size (use_proxy), None: full resolution
        self.proxy = None         # the ProxyMap build_solver() made for it

    def use_proxy(self):
        """Solve on a proxy if the mesh is above its Proxy Threshold (live runs only: a scripted run
        goes through at full resolution at once). True if it will."""
        self.proxy_target = proxy_size(self.num_vertices, self.applied["proxy_threshold"])
        return self.proxy_target is not None

    def release(self):
        """Remove the source's evaluated mesh copy unless a target adopted it (safe to repeat)."""
        self.source.release()

    def regions_for(self, settings, weights=None):
        """(face weights, None) of the slots' Regions, from ``weights`` (default: the group weights
        read at the start): Solver.set_face_weights' arguments (no vertex weights: the cubic method
        takes a vertex's strength from its faces, see styles.face_weights)."""
        weights = self.weights if weights is None else weights
        groups = [slot.vertex_group for slot in settings.styles]
        self.paint_steepness = paint_curve.steepness_of(settings)
        return styles.face_weights(self.arrays, weights, groups, settings.uncovered, self.paint_steepness), None

    @property
    def num_vertices(self):
        return self.arrays.num_vertices

    def changed(self):
        """Why the object is no longer what this plan read (None if it still is). The interface stays
        usable while a solver is set up on another thread, so it may have been edited or deleted."""
        try:
            if self.obj.data != self.mesh or len(self.mesh.vertices) != len(self.base_coords):
                return "its mesh was replaced or edited while Stylize was preparing; press Stylize again"
        except ReferenceError:
            return "it was deleted while Stylize was preparing"
        now = np.empty_like(self.base_coords)
        mesh_io.read_base_coords(self.mesh, now)
        if not np.array_equal(now, self.base_coords):
            return "its mesh was edited while Stylize was preparing; press Stylize again"
        return None

    def build_solver(self, progress=None):
        """The solver set up for this plan. Reads no Blender data, so it may run on any thread.

        progress: a gauss_core.Progress to watch (and cancel) the set-up from another thread;
        a cancelled set-up raises gauss_core.Cancelled, which is passed on."""
        options = dict(self.solver_options)
        if progress is not None:
            options["progress"] = progress
        coords, triangles, pins = self.arrays.coords, self.arrays.triangles, self.pins
        try:
            if self.proxy_target is not None:
                self.proxy = ProxyMap(self.gauss_core, coords, triangles, self.proxy_target)
                coords, triangles, pins = self.proxy.vertices, self.proxy.triangles, self.proxy.pins(pins)
            return self.gauss_core.Solver(coords, triangles, pinned=pins if len(pins) else None, **options)
        except self.gauss_core.Cancelled:
            raise
        except (ValueError, TypeError, RuntimeError, MemoryError) as exc:
            raise _solver_error(exc) from exc


def solver_changes(plan, obj, settings, applied, changed, weights):
    """What brings a solver from the settings ``applied`` (settings_io.to_dict) to ``settings``, given
    ``changed`` (fields.changes) and the group ``weights``: (calls, pins). calls: the solver calls in the
    order they must run (run_calls); pins: the new pinned vertices, or None. Reads only ``plan``,
    ``settings`` and the arrays given, and touches no solver, so a run's recorded changes can be turned
    into calls on the main thread and made on a worker (rerun.py). Raises SettingsError on bad pins."""
    calls = []
    new_styles = faces = pins = None
    if Live.STYLES in changed:
        new_styles = styles.make_styles(plan.gauss_core, settings.styles)
    if Live.REGIONS in changed or ((Live.SETTER in changed or Live.CURVE in changed) and
                                   plan.paint_steepness != paint_curve.steepness_of(settings)):
        # The paint curve follows Method, Lambda, Resolution Independent and old_paint_curve.
        faces = plan.regions_for(settings, weights)
    if Live.PINS in changed:
        pins = styles.pinned_vertices(weights, settings.pin_group)
        check_pins(obj, pins, plan.arrays.triangles)
    if Live.SETTER in changed:
        # Only those that changed: setting one ends the solver's converged state (Tolerance
        # excepted, which only changes what `converged` says), so a run resumes only when it should.
        for field in schema.SOLVER_SETTERS:
            value = field.read(settings)
            if value != applied[field.name]:
                calls.append((setattr, field.name, value))
    # Never let face indices point past the style list, in either order.
    if new_styles is not None and len(new_styles) >= len(applied["styles"]):
        calls.append(("set_styles", new_styles))
        new_styles = None
    if faces is not None:
        calls.append(("set_face_weights",) + tuple(faces))
    if new_styles is not None:
        calls.append(("set_styles", new_styles))
    return calls, pins


def run_calls(solver, calls):
    """Make solver_changes' calls on ``solver``."""
    for call in calls:
        if call[0] is setattr:
            setattr(solver, call[1], call[2])
        else:
            getattr(solver, call[0])(*call[1:])


class Session:
    def __init__(self, plan, solver=None, background_pins=False):
        """plan: a Plan, or an object to plan for now; solver: plan.build_solver()'s result,
        built here when not given; background_pins: a Pin Group change re-factors on a worker
        thread (solver_setup.PinsSetup) while the session waits, instead of inside sync_settings()."""
        if not isinstance(plan, Plan):
            plan = Plan(plan)
        try:
            self._start(plan, solver, background_pins)
        finally:
            plan.release()  # the evaluated copy, unless the target took it over

    def _start(self, plan, solver, background_pins):
        if solver is None:
            solver = plan.build_solver()
        self.plan = plan
        self.obj, self.mesh, self.gauss_core = plan.obj, plan.mesh, plan.gauss_core
        self.arrays, self.weights, self.target = plan.arrays, plan.weights, plan.target
        self.applied = plan.applied
        # A live run above the Proxy Threshold solves on plan.proxy (proxy_run.py) until finish_task()'s
        # full-resolution solver takes over; the mesh's pinned vertices stay in fine_pins meanwhile.
        self.proxy = plan.proxy
        self.fine_pins = plan.pins
        try:
            solver.set_styles(plan.styles)
            solver.set_face_weights(*self._on_solver(plan.regions))
        except (ValueError, TypeError) as exc:
            raise _solver_error(exc) from exc
        self.solver = solver
        # The solver writes its result straight into this buffer every step (through the proxy's
        # buffer and its transfer on a proxy; on a worker, into buffers swapped with these, take_step):
        # preallocated, so a tick allocates nothing.
        self.result = np.empty_like(self.arrays.coords)
        self._proxy_result = None if self.proxy is None else np.empty((self.proxy.num_vertices, 3), np.float32)
        # A live run on a proxy steps on a worker thread (start_step / take_step / write_taken; made at
        # the first start_step); None: steps run on the calling thread (step()). The worker writes its
        # step into buffers of its own, which take_step swaps with result and _proxy_result (no copy, no
        # allocation); _worker_range is the min and max of its result (the blow-up check, off the main
        # thread too).
        self.stepper = None
        self._worker_result = self._worker_proxy = None
        self._worker_range = [0.0, 0.0]
        self._taken_range = (0.0, 0.0)  # _worker_range of the step take_step took, for write_taken
        self._readouts = {}      # the solver's read-outs when the worker's step began (_readout)
        self._queued_pins = []   # pin targets moved while the worker stepped, in order (move_pins)
        # Coordinates beyond these (MAX_EXTENT mesh sizes around the rest mesh) mean a blow-up.
        lower, upper = float(self.arrays.coords.min()), float(self.arrays.coords.max())
        margin = MAX_EXTENT * max(upper - lower, 1e-30)
        self.bounds = (lower - margin, upper + margin)
        self.steps = 0
        self.finished_on_proxy = False  # finish_on() went on at full resolution after a proxy
        # Every vertex Avoid Self-Intersections has held back in some step of this run (Select Held
        # Faces): the set of one step comes and goes from step to step, where the run is held does not.
        self._ever_held = np.zeros(self.arrays.num_vertices, bool)
        self._runaways = 0             # solver.runaway_steps at the last step
        self._last_runaway = None      # self.steps when a step last ran away (unstable)
        self.step_ms = deque(maxlen=TIMINGS_KEPT)  # ms per step, of the last TIMINGS_KEPT step() / step_until()
        self.background_pins = background_pins
        self.pins_setup = None         # a PinsSetup running or not yet looked at
        # Counts the Pin Group changes sent to the solver (and the handle moves it refused after a worker's
        # step, _move_queued_pins): handles.Handles built before one are stale.
        self.pin_changes = 0
        self._mode = self.obj.mode  # the object's mode at the last tick: a return from Weight Paint re-reads weights
        self._pin_group_before = None  # applied["pin_group"] before it
        self._fine_pins_before = self.fine_pins  # fine_pins before it
        # What Replay needs of this run (recipe_store.py): how it started, and each change at its step.
        self.recipe = {"settings": self.applied, "weights": self._used_weights(self.applied),
                       "output": self.target.kind, "use_modifiers": plan.source.evaluated, "events": []}
        self.target.prepare()  # first change to the object: everything above succeeded

    # -- a proxy ---------------------------------------------------------------

    def _on_solver(self, regions):
        """Solver.set_face_weights' arguments of the mesh's ``regions`` for the solver that runs."""
        if self.proxy is None:
            return regions
        faces, _vertices = regions
        return self.proxy.face_weights(self.arrays.triangles, faces), None

    def _pins_on_solver(self, fine_pins):
        return fine_pins if self.proxy is None else self.proxy.pins(fine_pins)

    @property
    def solve_coords(self):
        """(#S, 3) rest positions of the mesh the solver runs on: the proxy's or the whole mesh's."""
        return self.arrays.coords if self.proxy is None else self.proxy.vertices

    @property
    def solve_triangles(self):
        """(#G, 3) triangles of the mesh the solver runs on (what the solver's pin indices refer to)."""
        return self.arrays.triangles if self.proxy is None else self.proxy.triangles

    @property
    def on_proxy(self):
        return self.proxy is not None

    def finish_task(self):
        """A proxy run's full-resolution solver, to be built on a worker thread: (weight, text, run) for
        solver_setup.BackgroundSetup; run(progress) returns the solver. Read here, on the main thread:
        the settings the run has now, the mesh's pins and where the proxy's pins put them."""
        self.stop_stepping()
        self._stop_pins()
        options = {field.name: self.applied[field.name] for field in schema.SOLVER_SETTERS}
        pins = np.asarray(self.fine_pins, np.int32)
        targets = self.proxy.fine_pin_targets(pins, self.arrays.coords, self.solver.pinned,
                                              self.solver.pin_positions, self.proxy.vertices)
        settings = self.obj.gauss_stylization
        regions = self.plan.regions_for(settings, self.weights)
        new_styles = styles.make_styles(self.gauss_core, settings.styles)
        coords, triangles = self.arrays.coords, self.arrays.triangles
        start = self.result  # the proxy's transfer; nothing writes it until finish_on()

        def build(progress):
            # The warm start too, off the main thread: with Resolution Independent set_vertices
            # settles the bending term's rotations for the start (seconds at a million vertices).
            try:
                solver = self.gauss_core.Solver(coords, triangles, pinned=pins if len(pins) else None,
                                                progress=progress, **options)
                solver.set_styles(new_styles)
                solver.set_face_weights(*regions)
                solver.set_vertices(start)
                if len(targets):
                    solver.set_pin_positions(targets)
            except self.gauss_core.Cancelled:
                raise
            except (ValueError, TypeError, RuntimeError, MemoryError) as exc:
                raise _solver_error(exc) from exc
            return solver
        return (self.arrays.num_vertices, "Preparing %s vertices at full resolution"
                % "{:,}".format(self.arrays.num_vertices), build)

    def leave_proxy(self):
        """Once finish_task() has read what the finish needs of the proxy (and stopped its worker):
        its map and the worker's buffers go, so that they do not sit beside the full-resolution solver
        being built (at 2M vertices about 0.2 GB of the finish's peak). Nothing steps until
        finish_on(); the proxy's solver stays until then for what the status reads of it, and a cancel
        restores the mesh without either."""
        self.proxy = self.plan.proxy = self._proxy_result = None
        self._worker_result = self._worker_proxy = None

    def finish_on(self, solver):
        """Go on at full resolution with ``solver`` (finish_task()'s result: styled, weighted, pinned
        and warm-started from the shape the proxy's transfer gave the mesh); steps from now on write
        the mesh directly."""
        self.solver, self.proxy, self._proxy_result = solver, None, None
        self.pin_changes += 1  # handles of the proxy's pins are stale
        self.finished_on_proxy = True

    # -- running ---------------------------------------------------------------

    @property
    def busy(self):
        """The PinsSetup the solver is busy with (no step until it is done), or None."""
        setup = self.pins_setup
        return setup if setup is not None and not setup.done else None

    def sync_settings(self, repainted=None):
        """Send changed settings to the solver. Returns None, or why it cannot run now.
        Not while ``busy``. repainted: what new weights in self.weights change (a replayed repaint;
        default: what the artist's Weight Paint strokes changed, _repainted())."""
        problem = self._finish_pins()
        if problem is not None:
            return problem
        settings = self.obj.gauss_stylization
        wanted = to_dict(settings)
        repainted = self._repainted(settings) if repainted is None else repainted
        changed = changes(schema.OBJECT, self.applied, wanted) | repainted
        if changed or self._group_deleted():
            try:
                check_settings(self.obj, settings, self.weights)
                self._apply(settings, changed)
            except SettingsError as exc:
                return str(exc)
            except (ValueError, TypeError) as exc:
                return "The solver rejected a setting: %s" % exc
            event = {"step": self.steps, "settings": wanted}
            if repainted:
                event.update(repainted=sorted(kind.name for kind in repainted), weights=self._used_weights(wanted))
            self.recipe["events"].append(event)
        self.applied = wanted
        return None

    def move_pins(self, targets):
        """New targets ((#P,3), object space) for the pinned vertices (a handle's drag, a script's pin
        targets), without re-factoring. Raises ValueError if the solver refuses them.

        While the worker steps (a proxy run) the move waits, in order, for the step to end
        (take_step), so that a drag never blocks the main thread; the solver then checks it, and a
        move it refuses is dropped and the handles rebuilt from the solver's targets (pin_changes)."""
        if self.stepper is not None and not self.stepper.idle:
            self._queued_pins.append(np.array(targets, np.float64))
            return
        self._move_pins_now(targets)

    def _move_pins_now(self, targets):
        before = self.mesh_pin_targets()
        self.solver.set_pin_positions(targets)
        # Only the rows that moved (a handle moves its part's pins): a long drag stays small in the recipe.
        now = self.mesh_pin_targets()
        rows = np.flatnonzero((now != before).any(axis=1)) if len(before) == len(now) else np.arange(len(now))
        self.recipe["events"].append({"step": self.steps, "rows": recipe_store.pack(rows, np.int64),
                                      "pins": recipe_store.pack(now[rows], np.float64)})

    def mesh_pin_targets(self):
        """The pin targets a recipe records: the mesh's (on a proxy: where the proxy's put them), so a
        run that re-makes it at full resolution (Follow Edits) moves the mesh's pins."""
        if self.proxy is None:
            return np.asarray(self.solver.pin_positions, np.float64)
        return self.proxy.fine_pin_targets(self.fine_pins, self.arrays.coords, self.solver.pinned,
                                           self.solver.pin_positions, self.proxy.vertices)

    def replay_event(self, event):
        """Make a recorded change (recipe_store.py) again, as the run it was recorded in made it."""
        if "pins" in event:
            targets = np.array(self.solver.pin_positions, np.float64)
            targets[recipe_store.unpack(event["rows"])] = recipe_store.unpack(event["pins"])
            self.move_pins(targets)
            return
        apply_dict(self.obj.gauss_stylization, event["settings"])
        repainted = set()
        if "weights" in event:
            self.weights = dict(self.weights, **{g: recipe_store.unpack(w) for g, w in event["weights"].items()})
            repainted = {Live[name] for name in event["repainted"]}
        problem = self.sync_settings(repainted)
        if problem is not None:
            raise SettingsError("Replay of '%s' stopped at step %d: %s" % (self.name, self.steps, problem))

    def _used_weights(self, applied):
        """The weights of the groups ``applied`` (settings_io.to_dict) reads: Regions and the Pin Group."""
        groups = {slot["vertex_group"] for slot in applied["styles"]} | {applied["pin_group"]}
        return {g: recipe_store.pack(self.weights[g], np.float32) for g in sorted(groups) if g in self.weights}

    @property
    def painting(self):
        """Is the object in Weight Paint mode? A live run holds it still meanwhile, so that strokes
        land where the artist sees the surface; they are read when it leaves (_repainted)."""
        return self._mode == 'WEIGHT_PAINT'

    def _repainted(self, settings):
        """What Weight Paint strokes changed, once the artist has left Weight Paint mode: {Live.REGIONS}
        if a Region's weights changed, with Live.PINS if the Pin Group's pinned vertices did (self.weights
        then holds the new weights); else an empty set. Blender signals no change of vertex-group
        weights, and reading them walks every vertex in Python, so they are read once per return from
        Weight Paint, not per stroke. A mesh whose modifiers change its topology (Use Modifiers) keeps
        the weights read at the start."""
        mode = self.obj.mode
        left = self._mode == 'WEIGHT_PAINT' and mode != 'WEIGHT_PAINT'
        self._mode = mode
        if not left or not self.plan.source.same_topology:
            return set()
        fresh = mesh_io.read_group_weights(self.obj)
        old, self.weights = self.weights, fresh

        def differs(group):
            if not group:
                return False
            before, now = old.get(group), fresh.get(group)
            return before is None or now is None or not np.array_equal(before, now)
        found = set()
        if any(differs(slot.vertex_group) for slot in settings.styles):
            found.add(Live.REGIONS)
        pin_group = settings.pin_group
        if differs(pin_group) and not np.array_equal(styles.pinned_vertices(old, pin_group),
                                                     styles.pinned_vertices(fresh, pin_group)):
            found.add(Live.PINS)
        return found

    def _group_deleted(self):
        """Is a vertex group the applied settings use gone from the object? (A few name look-ups.)"""
        groups = self.obj.vertex_groups
        if self.applied["pin_group"] and self.applied["pin_group"] not in groups:
            return True
        return any(slot["vertex_group"] and slot["vertex_group"] not in groups for slot in self.applied["styles"])

    def _apply(self, settings, changed):
        calls, pins = solver_changes(self.plan, self.obj, settings, self.applied, changed, self.weights)
        if self.proxy is not None:  # the mesh's Regions and pins, on the proxy the solver runs
            calls = [("set_face_weights",) + tuple(self._on_solver(call[1:])) if call[0] == "set_face_weights"
                     else call for call in calls]
        run_calls(self.solver, calls)
        if pins is None:
            return
        self._fine_pins_before, self.fine_pins = self.fine_pins, pins
        pins = self._pins_on_solver(pins)
        self.pin_changes += 1
        if self.background_pins:  # last: the solver is not to be touched until it is done
            self._pin_group_before = self.applied["pin_group"]
            self.pins_setup = PinsSetup(self, pins)
        else:
            self.solver.set_pins(pins)

    def _finish_pins(self):
        """Once a PinsSetup is done: None, or why it failed (the solver keeps its old pins, and the
        next sync tries the Pin Group again)."""
        setup, self.pins_setup = self.pins_setup, None
        if setup is None or not isinstance(setup.results[0], Exception):
            return None
        self.applied = dict(self.applied, pin_group=self._pin_group_before)
        self.fine_pins = self._fine_pins_before
        return str(setup.results[0])

    def _stop_pins(self):
        if self.pins_setup is not None:
            self.pins_setup.cancel()
            self.pins_setup = None

    def start_from(self, coords):
        """Continue from ``coords`` ((#V,3)) instead of the current shape: the rest shape and the
        factorization stay (a warm start, see bake.py)."""
        self.solver.set_vertices(coords)

    # The solver's read-outs that the run's status shows at every redraw. Each locks the solver, so
    # while the worker steps they are the ones read when its step began (start_step): the main thread
    # never waits for a step to say how far the run is.
    READOUTS = ("converged", "held_back", "last_reldv", "held_vertices")

    def _readout(self, name):
        if self.stepper is not None and not self.stepper.idle:
            return self._readouts[name]
        return getattr(self.solver, name)

    @property
    def converged(self):
        """Did the last step move the mesh by less than the Tolerance, with nothing changed since?
        (The solver forgets it at any change of settings, styles or pins.)"""
        return self._readout("converged")

    @property
    def held_back(self):
        """Did the run stop moving only because Avoid Self-Intersections holds it (not converged)?"""
        return self._readout("held_back")

    @property
    def at_rest(self):
        """Converged or held back: another step would not move the mesh, until something changes."""
        return self.converged or self.held_back

    @property
    def reldv(self):
        """The last step's relative change (inf before the first step and after a change)."""
        return self._readout("last_reldv")

    @property
    def held_vertices(self):
        """How many vertices Avoid Self-Intersections held back in the last step."""
        return self._readout("held_vertices")

    def step(self, count=1):
        """Run ``count`` solver iterations and write the result to the target."""
        start = time.perf_counter()
        self.solver.step(count)
        self._stepped(count, start)

    def step_until(self, max_steps):
        """Step until converged (the solver's tolerance, the object's Tolerance), at most ``max_steps``
        times; write the result. Returns the number of steps taken."""
        start = time.perf_counter()
        count = self.solver.step_until(None, max_steps)
        if count:
            self._stepped(count, start)
        return count

    @property
    def unstable(self):
        """Did a step in the last UNSTABLE_STEPS run away (Solver.runaway_steps: the edge pull grew the
        mesh, and the step fell back to plain ARAP)? Strongly obtuse triangles at a high Lambda or ADMM
        Iterations do that; the shape stays bounded but does not settle."""
        return self._last_runaway is not None and self.steps - self._last_runaway < UNSTABLE_STEPS

    @property
    def held_anywhere(self):
        """Sorted (#H,) indices of the vertices the guard has held back in some step of this run."""
        return np.flatnonzero(self._ever_held)

    # -- stepping on a worker thread (a live run on a proxy, proxy_stepper.py) ---------------

    @property
    def stepping(self):
        """Is the worker's step still running? (Nothing of the solver is to be touched meanwhile.)"""
        return self.stepper is not None and self.stepper.pending and not self.stepper.idle

    @property
    def step_done(self):
        """Has the worker finished a step that take_step() has not taken yet?"""
        return self.stepper is not None and self.stepper.done

    def start_step(self):
        """Start the next step on the worker (not while ``stepping`` or ``step_done``); returns at once."""
        if self.stepper is None:
            self._worker_result = np.empty_like(self.result)
            self._worker_proxy = np.empty_like(self._proxy_result)
            self.stepper = ProxyStepper(self._worker_step)
        for name in self.READOUTS:
            self._readouts[name] = getattr(self.solver, name)
        self.stepper.start()

    def _worker_step(self):
        """One step on the worker: the solver, the proxy and the worker's own buffers only."""
        self.solver.step(1)
        self.solver.vertices_into(self._worker_proxy)
        self.proxy.proxy.transfer(self._worker_proxy, self._worker_result)
        self._worker_range[0], self._worker_range[1] = self._worker_result.min(), self._worker_result.max()

    def take_step(self):
        """Once ``step_done``: the step's buffers become result and _proxy_result (for write_taken), the
        step is counted, then the pin moves that waited for it are made. Raises what the step raised."""
        stepper = self.stepper
        stepper.pending = False
        error, stepper.error = stepper.error, None
        if error is not None:
            raise error
        self.result, self._worker_result = self._worker_result, self.result
        self._proxy_result, self._worker_proxy = self._worker_proxy, self._proxy_result
        self._taken_range = tuple(self._worker_range)
        self._count(1, stepper.ms)
        self._move_queued_pins()

    def write_taken(self):
        """Write the step take_step() took (transferred on the worker) into the mesh, while the next runs."""
        self._check_and_write(*self._taken_range)

    def stop_stepping(self):
        """End the worker (waiting for its step, which is dropped: the mesh keeps the last one written,
        what the artist saw) and make the pin moves that waited. The solver is this thread's again."""
        stepper, self.stepper = self.stepper, None
        if stepper is not None:
            stepper.stop()
            self._move_queued_pins()

    def _move_queued_pins(self):
        queued, self._queued_pins = self._queued_pins, []
        for targets in queued:
            try:
                self._move_pins_now(targets)
            except ValueError:  # refused (not finite, too far): the handles show the solver's targets again
                self.pin_changes += 1

    # -- counting and writing a step ---------------------------------------------------

    def _stepped(self, count, start):
        self._count(count, (time.perf_counter() - start) * 1000.0 / max(count, 1))
        if self.proxy is None:
            self.solver.vertices_into(self.result)
        else:
            self.solver.vertices_into(self._proxy_result)
        self._write()

    def _count(self, count, ms):
        """Book ``count`` steps just taken (``ms`` each): the step count, runaways, held vertices."""
        self.step_ms.append(ms)
        self.steps += count
        runaways = self.solver.runaway_steps  # since the solver's last reset: it may go down
        if runaways > self._runaways:
            self._last_runaway = self.steps
        self._runaways = runaways
        if self.solver.held_vertices:  # the last of the ``count`` steps: a tick steps once
            held = self.solver.held_vertex_indices
            self._ever_held[held if self.proxy is None else self.proxy.fine[held]] = True

    def _write(self):
        """Write the step read out (self.result, or on a proxy its transfer of self._proxy_result) into the
        target, unless it blew up."""
        if self.proxy is not None:
            self.proxy.proxy.transfer(self._proxy_result, self.result)
        # Never write NaN or a blown-up shape into the artist's mesh: two reductions, which
        # propagate NaN and allocate nothing.
        self._check_and_write(self.result.min(), self.result.max())

    def _check_and_write(self, low, high):
        """Write self.result, whose coordinates lie within [low, high], unless it blew up."""
        if not (self.bounds[0] <= low and high <= self.bounds[1]):
            raise SettingsError(
                "The solver produced invalid positions after step %d (%s), so Stylize stopped. "
                "This is a defect of the solver, not of your settings: please report it with the mesh"
                % (self.steps, "not finite" if not (np.isfinite(low) and np.isfinite(high))
                   else "more than %g times the mesh's size away" % MAX_EXTENT))
        self.target.write(self.result)

    # -- ending ----------------------------------------------------------------

    def keep(self):
        """Keep the result; remember the start coordinates for the Reset operator."""
        self.stop_stepping()  # the result is the last step written
        self._stop_pins()  # a Pin Group change still being prepared never reached the result
        self.target.keep()
        rest_store.capture(*self.target.rest)
        self._record()

    def _record(self):
        """Add this kept run to the mesh's recipe (recipe_store.py). Replay covers the Mesh and Shape
        Key outputs of the base mesh: a run with Use Modifiers writes where a replay from the rest
        shape cannot follow, so it ends the recipe. A New Object run leaves the mesh as it was, and
        its recipe with it; its own recipe goes on the copy (follow_store.py)."""
        if self.steps == 0:
            return
        # A proxy run's steps and pin moves were the proxy's: a replay at full resolution cannot repeat
        # them, so it leaves no recipe (a New Object copy of one does not follow its source).
        on_proxy = self.finished_on_proxy or self.proxy is not None
        if self.target.kind == output.NewObjectTarget.kind:  # on the copy: Follow Edits and Replay re-make it
            if not on_proxy:
                follow_store.save(self.target.obj, self.obj, dict(self.recipe, steps=self.steps), self.arrays)
            return
        follow_store.forget(self.obj)  # a copy moved by a run of its own no longer follows its source
        if self.recipe["use_modifiers"] or on_proxy:
            recipe_store.save(self.mesh, None)
            return
        start = self.arrays.coords
        recipe_store.add_run(self.mesh, start, dict(
            self.recipe, steps=self.steps, start_fingerprint=recipe_store.fingerprint(start),
            result_fingerprint=recipe_store.fingerprint(self.result)))

    def cancel(self):
        """Put back exactly what was there before the run, as far as it still exists.

        The mesh is restored even when its object was deleted during the run:
        another object may share it, and undo reuses the mesh as it is in memory.
        A freed mesh, or one whose vertex count changed, is left alone (output.py).
        """
        self.stop_stepping()  # the worker never writes the mesh; it only must not outlive the run
        self._stop_pins()
        self.target.restore()

    def hold(self):
        """Show what cancel() would leave, for a file being saved; the run goes on after resume()."""
        self.target.hold()

    def resume(self):
        """After a save: the result of the last step back where hold() took it away."""
        self.target.resume(self.result if self.steps else None)  # None: nothing written yet

    def object_alive(self):
        try:
            return self.obj.data == self.mesh and self.target.alive()
        except ReferenceError:  # the object or mesh was deleted while running
            return False

    @property
    def name(self):
        """The object's name now, or the one it had when the run started if it is gone."""
        try:
            return self.obj.name
        except ReferenceError:
            return self.plan.name
