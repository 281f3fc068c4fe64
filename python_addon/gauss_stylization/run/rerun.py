"""A New Object copy's kept run (mesh/follow_store.py) made again from its source's current shape:
what Replay does on a copy, and what Follow Edits (follow.py) runs on a worker thread.

``prepare(copy, source)`` reads everything on the main thread (the recorded settings and weights
put through a session.Plan, as the kept run read its own, and each change the run had while it ran
turned into its solver calls); ``Job(prepared).compute()`` then runs the solver from those arrays
alone, as session.Session ran it (set-up, styles, Regions, one step at a time, each change at its
step), so it may run on any thread and its result is the kept run's bit for bit on an unchanged
source. A source whose topology changed is re-run from scratch: the recipe's settings on the new
mesh, with the source's own vertex groups instead of the recorded weights, which fit it no longer.
"""

import threading

import bpy
import numpy as np

from ..errors import SettingsError
from ..mesh import follow_store, mesh_io, recipe_store, source as sources
from ..settings import schema
from ..settings.fields import Live, changes
from ..settings.settings_io import apply_dict, to_dict
from ..settings.validation import check_settings
from ..settings.versioning import as_recorded, bring_stamped_up_to_date
from .session import Plan, run_calls, solver_changes


class _NoTarget:
    """A Plan's target where nothing is written through a Session (the caller writes the result)."""
    kind = 'NEW_OBJECT'


def problem(copy):
    """Why ``copy``'s run cannot be made again (None if it can). A look-up only, as replay.problem: the
    panel asks it at every redraw."""
    if not follow_store.has(copy):
        return "'%s' is not a kept New Object result with a recipe" % copy.name
    source = follow_store.source_of(copy)
    if source is None:
        return "The source of '%s' was deleted" % copy.name
    return None


class Prepared:
    """What a Job needs, read on the main thread: plan (session.Plan), steps, notes (what the
    artist is told: a topology change), source_coords (what was stylized, (#V,3) float32), and
    changes: {step: [change]}, the run's recorded changes as _recorded_changes made them."""

    def __init__(self, plan, steps, notes, mesh=None, changes=None):
        self.plan, self.steps, self.notes = plan, steps, notes
        self.changes = changes or {}
        self.topology = follow_store.topology(plan.arrays)
        self.mesh = mesh  # the evaluated mesh to become the copy's after a topology change (Use Modifiers)
        self.source_coords = plan.arrays.coords
        self.num_vertices = plan.num_vertices


def prepare(copy, source_input=None):
    """A Prepared re-run of ``copy``'s recipe on ``source_input`` (a mesh/source.Source; default: read
    from the source now). Raises SettingsError (problem()). Main thread."""
    why = problem(copy)
    stored = follow_store.load(copy) if why is None else None
    if stored is None:
        raise SettingsError(why or "The recipe of '%s' is from another version of the add-on" % copy.name)
    source, stored = stored
    run = stored["run"]
    if source_input is None:
        source_input = sources.read(source, run["use_modifiers"])
    notes = []
    changed = follow_store.topology(source_input.arrays) != stored["topology"]
    applied = as_recorded(run["settings"])
    applied.pop("follow_edits", None)  # the copy's own switch, not a setting of the run
    weights = {group: recipe_store.unpack(w) for group, w in run["weights"].items()}
    if changed:
        notes.append("the source's vertices or faces changed: re-run from scratch")
        weights = None  # the recorded ones fit the old mesh: the source's own groups now
        groups = {slot["vertex_group"] for slot in applied["styles"]} | {applied["pin_group"]}
        missing = sorted(g for g in groups if g and g not in source_input.weights)
        if missing:
            notes.append("without the vertex group%s %s, which the source no longer has"
                         % ("s" * (len(missing) > 1), ", ".join("'%s'" % g for g in missing)))
            applied["styles"] = [dict(slot, vertex_group="" if slot["vertex_group"] in missing else
                                      slot["vertex_group"]) for slot in applied["styles"]]
            if applied["pin_group"] in missing:
                applied["pin_group"] = ""
    settings = copy.gauss_stylization
    bring_stamped_up_to_date(settings)  # before the snapshot restored below (replay.py says why)
    before = to_dict(settings)
    try:
        apply_dict(settings, applied)
        plan = Plan(copy, source=source_input, target=_NoTarget(), weights=weights)
        recorded = _recorded_changes(copy, plan, run["events"], fits=not changed, notes=notes)
    except BaseException:
        source_input.release()
        raise
    finally:
        apply_dict(settings, before)
    # The evaluated copy (Use Modifiers) becomes the copy's mesh if the topology changed; else the job
    # reads only its arrays.
    mesh = source_input.adopt_mesh() if changed else None
    plan.release()
    return Prepared(plan, run["steps"], notes, mesh, recorded)


def _recorded_changes(copy, plan, events, fits, notes):
    """The changes a run had while it ran (recipe_store.py's events: settings, repainted weights, pin
    moves) as what Job makes at each step: {step: [("calls", calls, pins) or ("pins", rows, targets)]},
    the same solver calls, in the same order, as the kept run and Replay made (Session.replay_event).
    Each settings change is put through session.solver_changes here, on the main thread, with the
    copy's settings set as they were at that step (the caller puts them back). ``fits``: the recorded
    weights and pinned rows fit the source's mesh; after a topology change they do not, and only the
    settings changes are made again (the source's own weights for all of them). A handle's moves are
    the positions the artist dragged it to, as Replay makes them. Raises SettingsError."""
    settings = copy.gauss_stylization
    applied, weights = plan.applied, plan.weights
    recorded, dropped = {}, False
    for event in events:
        at = recorded.setdefault(event["step"], [])
        if "pins" in event:
            if fits:
                at.append(("pins", recipe_store.unpack(event["rows"]), recipe_store.unpack(event["pins"])))
            dropped = dropped or not fits
            continue
        changed_settings = dict(event["settings"])
        changed_settings.pop("follow_edits", None)  # the copy's own switch, as in prepare()
        apply_dict(settings, changed_settings)
        repainted = set()
        if "weights" in event:
            if fits:
                weights = dict(weights, **{g: recipe_store.unpack(w) for g, w in event["weights"].items()})
                repainted = {Live[name] for name in event["repainted"]}
            dropped = dropped or not fits
        wanted = to_dict(settings)
        changed = changes(schema.OBJECT, applied, wanted) | repainted
        if changed:
            try:
                check_settings(copy, settings, weights)
            except SettingsError as exc:
                raise SettingsError("The run of '%s' cannot be made again at its step %d: %s"
                                    % (copy.name, event["step"], exc)) from exc
            at.append(("calls",) + solver_changes(plan, copy, settings, applied, changed, weights))
        applied = wanted
    if dropped:
        notes.append("without the run's repaints and handle moves, which fit the old mesh")
    return recorded


def _make(solver, change):
    """One of _recorded_changes' changes, made on ``solver``."""
    if change[0] == "pins":
        _kind, rows, targets = change
        now = np.array(solver.pin_positions, np.float64)
        now[rows] = targets
        solver.set_pin_positions(now)
        return
    _kind, calls, pins = change
    run_calls(solver, calls)
    if pins is not None:
        solver.set_pins(pins)


class Job:
    """One re-run, on the calling thread (compute()) or a worker (start()). ``cancel()`` stops it
    between steps (or during the solver's set-up); a cancelled job has no result."""

    def __init__(self, prepared):
        self.prepared = prepared
        self.result = None      # (#V,3) float32 once done
        self.error = None       # a SettingsError that stopped it
        self._cancelled = False
        self._progress = None
        self._thread = None

    def compute(self):
        plan = self.prepared.plan
        gauss_core = plan.gauss_core
        self._progress = gauss_core.Progress()
        if self._cancelled:
            return None
        try:
            solver = plan.build_solver(self._progress)
            solver.set_styles(plan.styles)
            solver.set_face_weights(*plan.regions)
            result = np.empty_like(plan.arrays.coords)
            recorded = self.prepared.changes
            for step in range(self.prepared.steps):  # one at a time, as the kept run and Replay step
                if self._cancelled:
                    return None
                for change in recorded.get(step, ()):
                    _make(solver, change)
                solver.step(1)
            solver.vertices_into(result)
        except gauss_core.Cancelled:
            return None
        except SettingsError as exc:
            self.error = exc
            return None
        except (ValueError, TypeError, RuntimeError, MemoryError) as exc:
            self.error = SettingsError("The solver cannot re-run this copy: %s" % exc)
            return None
        if not np.isfinite(result).all():
            self.error = SettingsError("The solver produced positions that are not finite")
            return None
        self.result = result
        return result

    def start(self):
        self._thread = threading.Thread(target=self.compute, name="Gauss Follow Edits", daemon=True)
        self._thread.start()
        return self

    @property
    def done(self):
        return self._thread is not None and not self._thread.is_alive()

    def cancel(self):
        """Stop soon; does not wait."""
        self._cancelled = True
        progress = self._progress
        if progress is not None:
            progress.cancel()

    def wait(self, timeout=None):
        if self._thread is not None:
            self._thread.join(timeout)


def replay_copy(copy):
    """Replay of a copy: its run again from the source's current shape, written into the copy at once.
    Returns (notes, steps). Raises SettingsError."""
    prepared = prepare(copy)
    job = Job(prepared)
    job.compute()
    if job.error is not None:
        raise job.error
    if not write(copy, prepared, job.result):
        raise SettingsError("The source of '%s' changed its vertices while it was replayed" % copy.name)
    return prepared.notes, prepared.steps


def write(copy, prepared, coords):
    """Write ``coords`` (a Job's result for ``prepared``) into the copy's mesh; after a topology change
    the copy first gets a mesh of the new topology (the source's, as New Object made it). False if
    nothing fits any more (the source changed again meanwhile). Main thread."""
    mesh = copy.data
    if len(mesh.vertices) != len(coords) or prepared.mesh is not None or _topology_differs(mesh, prepared.topology):
        fresh = prepared.mesh
        prepared.mesh = None
        if fresh is None:
            source = follow_store.source_of(copy)
            if source is None or len(source.data.vertices) != len(coords):
                return False
            fresh = source.data.copy()
        if len(fresh.vertices) != len(coords):
            bpy.data.meshes.remove(fresh)
            return False
        fresh.name, old = mesh.name, mesh
        copy.data = fresh
        if old.users == 0:
            bpy.data.meshes.remove(old)
        mesh = fresh
        _written[mesh.as_pointer()] = prepared.topology
    return write_coords(copy, coords)


def write_coords(copy, coords):
    """Write ``coords`` into the copy's mesh as it is (and its reference key); False if the vertex
    count differs."""
    mesh = copy.data
    if len(mesh.vertices) != len(coords):
        return False
    mesh_io.write_vertex_coords(mesh, coords)
    key = mesh_io.base_key(mesh)
    if key is not None:
        mesh_io.write_key_coords(key, coords)
    mesh_io.tag_changed(mesh)
    return True


# The topology (follow_store.topology) of the copies' meshes as last written, by mesh pointer: a write
# of the same topology again reads no corners (35K vertices: 36 ms of the main thread per write).
_written = {}


def _topology_differs(mesh, topology):
    if len(mesh.polygons) != topology["polygons"]:
        return True
    if _written.get(mesh.as_pointer()) == topology:
        return False
    corner_vertex, _polygon, sides = mesh_io.read_corners(mesh)
    mine = follow_store.topology(_Corners(len(mesh.vertices), len(mesh.polygons), corner_vertex, sides))
    if mine != topology:
        return True
    _written[mesh.as_pointer()] = topology
    return False


def forget_written():
    """After an undo or a file load: meshes are allocated anew, a pointer may name another mesh."""
    _written.clear()


class _Corners:
    """What follow_store.topology reads of a MeshArrays."""

    def __init__(self, num_vertices, num_polygons, corner_vertex, polygon_sides):
        self.num_vertices, self.num_polygons = num_vertices, num_polygons
        self.corner_vertex, self.polygon_sides = corner_vertex, polygon_sides
