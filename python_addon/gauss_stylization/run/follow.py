"""Follow Edits: a New Object copy with ``follow_edits`` on is made again from its source whenever the
source changes (Edit Mode, sculpting, modifiers, shape keys, the frame), as Replay would make it.

A depsgraph handler notes which followed sources changed geometry (never the copies: writing a copy
starts nothing); a timer waits until a source has been still for QUIET_SECONDS, so quick edits
coalesce, then reads it and starts a rerun.Job on a worker thread. A newer edit cancels the job
running. Meanwhile the copy shows a preview: the last exact result moved by the source's
displacement since, while the edits go on (every PREVIEW_SECONDS) and when the job starts. The timer writes the exact result when the job is done. The source's shape last
solved is remembered per copy, so a read that finds it unchanged (an undo of nothing, a frame that
moves nothing) solves nothing. Scripts and background mode call ``settle()`` to wait for the copies.
"""

import time

import bmesh
import bpy
import numpy as np

from .. import app_handlers
from ..errors import SettingsError
from ..mesh import follow_store, mesh_io, recipe_store, source as sources
from ..settings import schema
from . import rerun

# An edit is followed once its source has been still this long: a drag's mouse moves coalesce into
# one solve, and a pause is still felt as at once.
QUIET_SECONDS = 0.15
POLL_SECONDS = 0.05  # how often the timer looks at the workers and the quiet periods
# While edits go on (no quiet period yet) the copy's preview is moved at most this often: reading the
# source's coordinates takes the main thread ~30 ms on 35K vertices in Edit Mode.
PREVIEW_SECONDS = 0.2

# What happened, for tests and the status: jobs started, exact results written, jobs a newer edit
# cancelled, previews shown.
stats = {"started": 0, "finished": 0, "cancelled": 0, "previews": 0}


class Follower:
    """What is known of one copy (by name) between edits."""

    def __init__(self):
        self.fingerprint = None  # of the source's shape the last job started from
        self.use_modifiers = None
        self.input = None        # that shape ((#V,3) float32) and the exact result made from it:
        self.result = None       # the preview of the next edit moves the one by the other's change
        self.source = None       # the last full read (sources.Source): topology and weights for Edit Mode reads
        self.job = None          # rerun.Job running
        self.status = ""


_followers = {}   # copy name -> Follower
_dirty = {}       # copy name -> time.monotonic() of its source's latest change
_forced = set()   # copy names re-run even if their source reads as before (after an undo)
_previewed = {}   # copy name -> time.monotonic() of its last preview during edits


def status(copy):
    """What Follow Edits says about ``copy`` (the panel's line), "" if nothing."""
    follower = _followers.get(copy.name)
    return follower.status if follower is not None else ""


def panel_lines(obj):
    """The panel's lines about Follow Edits for ``obj``: its own status as a following copy, and as a
    source the status of each copy following it."""
    lines = []
    if obj.gauss_stylization.follow_edits and status(obj):
        lines.append(status(obj))
    for name in _followers:
        copy = bpy.data.objects.get(name)
        if copy is not None and copy != obj and copy.get(follow_store.SOURCE_KEY) == obj and status(copy):
            lines.append("'%s': %s" % (name, status(copy)))
    return lines


def _followed():
    """{pointer of a source Object or its Mesh: [copy names]} of every copy with Follow Edits on."""
    found = {}
    for obj in bpy.data.objects:
        if schema.FOLLOW_RECIPE_KEY not in obj.keys() or not obj.gauss_stylization.follow_edits:
            continue
        source = obj.get(follow_store.SOURCE_KEY)
        if source is None:
            continue
        for key in (source.as_pointer(), source.data.as_pointer() if source.data else None):
            if key:
                found.setdefault(key, []).append(obj.name)
    return found


def _mark(names, force=False):
    now = time.monotonic()
    for name in names:
        _dirty[name] = now
        if force:
            _forced.add(name)
    if names and not bpy.app.timers.is_registered(_tick):
        bpy.app.timers.register(_tick, first_interval=POLL_SECONDS)


@bpy.app.handlers.persistent
def _depsgraph_changed(_scene, depsgraph):
    followed = None
    for update in depsgraph.updates:
        if not update.is_updated_geometry:
            continue
        if followed is None:
            followed = _followed()
            if not followed:
                return
        names = followed.get(update.id.original.as_pointer())
        if names:
            _mark(names)


@bpy.app.handlers.persistent
def _frame_changed(*_args):
    names = [n for names in _followed().values() for n in names
             if n not in _followers or _followers[n].use_modifiers is not False]
    _mark(sorted(set(names)))


@bpy.app.handlers.persistent
def _undone(*_args):
    # Undo may bring back a copy's mesh as it was before its last result: re-run even if the source
    # reads as the last job's start.
    rerun.forget_written()
    _mark(sorted({n for names in _followed().values() for n in names}), force=True)


@bpy.app.handlers.persistent
def _loaded(*_args):
    for follower in _followers.values():
        if follower.job is not None:
            follower.job.cancel()
    _followers.clear()
    _dirty.clear()
    rerun.forget_written()
    _forced.clear()
    _mark(sorted({n for names in _followed().values() for n in names}))


def switched(obj):
    """Follow Edits of ``obj`` was turned on (catch up with the source) or off (stop; nothing removed)."""
    if obj.gauss_stylization.follow_edits:
        if follow_store.has(obj):
            _mark([obj.name])
        return
    _drop(obj.name)


def _drop(name):
    follower = _followers.pop(name, None)
    if follower is not None and follower.job is not None:
        follower.job.cancel()
        stats["cancelled"] += 1
    _dirty.pop(name, None)
    _previewed.pop(name, None)
    _forced.discard(name)


def _edit_coords(source, follower):
    """The edit mesh's coordinates ((#V,3) float32) while its counts are those last read, else None."""
    edit = bmesh.from_edit_mesh(source.data)
    known = follower.source
    if known is None or (len(edit.verts), len(edit.faces)) != (known.arrays.num_vertices, known.arrays.num_polygons):
        return None
    return np.fromiter((c for v in edit.verts for c in v.co), np.float32, count=3 * len(edit.verts)).reshape(-1, 3)


def _read(source, follower, use_modifiers):
    """The source's shape now (sources.Source). In Edit Mode the mesh's vertices are stale and the
    edit mesh is current: its coordinates, on the topology last read while the counts stay; a count
    that changes writes the edit mesh to the mesh first (the follower then reads its own write as
    unchanged)."""
    if use_modifiers:
        return sources.read(source, True)
    if source.mode == 'EDIT':
        coords = _edit_coords(source, follower)
        if coords is not None:
            return follower.source.moved(coords)
        source.update_from_editmode()
    return sources.read(source, False)


def _quick_coords(source, follower):
    """The source's coordinates now without its topology (a preview during edits), or None where
    that is not cheap (Use Modifiers) or the vertex count is not the one last read."""
    if follower.use_modifiers is not False or follower.source is None:
        return None
    if source.mode == 'EDIT':
        return _edit_coords(source, follower)
    mesh = source.data
    if len(mesh.vertices) != follower.source.arrays.num_vertices:
        return None
    coords = np.empty((len(mesh.vertices), 3), np.float32)
    mesh_io.read_base_coords(mesh, coords)
    return coords


def _seed(copy, follower, stored):
    """What a follower knows before its first job: the kept run's start (or the last exact re-run's,
    follow_store.save_start) and the copy's shape, its result."""
    if follower.fingerprint is not None:
        return
    follower.fingerprint = stored["rest_fingerprint"]
    follower.input = recipe_store.unpack(stored["rest"])
    coords = mesh_io.read_vertex_coords(copy.data)
    follower.result = coords if coords.shape == follower.input.shape else None


def _start(name):
    """Read the copy's source and start a job if it changed since the last one."""
    copy = bpy.data.objects.get(name)
    if copy is None or not follow_store.has(copy) or not copy.gauss_stylization.follow_edits:
        _drop(name)
        return
    follower = _followers.setdefault(name, Follower())
    why = rerun.problem(copy)
    if why is not None:
        follower.status = why
        return
    loaded = follow_store.load(copy)
    if loaded is None:
        follower.status = "The recipe of '%s' is from another version of the add-on" % name
        return
    source, stored = loaded
    run = stored["run"]
    follower.use_modifiers = run["use_modifiers"]
    try:
        src = _read(source, follower, run["use_modifiers"])
    except SettingsError as exc:
        follower.status = str(exc)
        return
    fingerprint = follow_store.fingerprint(src.arrays)
    _seed(copy, follower, stored)
    if fingerprint == follower.fingerprint and name not in _forced:
        src.release()
        return
    _forced.discard(name)
    try:
        prepared = rerun.prepare(copy, src)
    except SettingsError as exc:
        follower.status = str(exc)
        return
    if follower.job is not None:
        follower.job.cancel()
        stats["cancelled"] += 1
    if not prepared.notes:  # a topology change has no preview: nothing to move
        _preview(copy, follower, prepared.source_coords)
    follower.fingerprint = fingerprint
    if not src.evaluated:
        follower.source = src
    follower.job = rerun.Job(prepared).start()
    stats["started"] += 1
    follower.status = "Following '%s': re-running" % source.name


def _live_preview(name):
    """A preview while the edits go on (before the quiet period ends): the source's coordinates only."""
    follower = _followers.get(name)
    copy = bpy.data.objects.get(name)
    if follower is None or copy is None or not follow_store.has(copy) or not copy.gauss_stylization.follow_edits:
        return
    source = copy.get(follow_store.SOURCE_KEY)
    if source is None:
        return
    coords = _quick_coords(source, follower)
    if coords is not None:
        _preview(copy, follower, coords)


def _preview(copy, follower, start):
    """The last exact result moved as the source moved since (``start``: its coordinates now)."""
    if follower.input is None or follower.result is None or follower.input.shape != start.shape:
        return
    if rerun.write_coords(copy, follower.result + (start - follower.input)):
        stats["previews"] += 1


def _finish(name, follower):
    job, follower.job = follower.job, None
    copy = bpy.data.objects.get(name)
    if copy is None or not copy.gauss_stylization.follow_edits or not follow_store.has(copy):
        _drop(name)
        return
    if job.error is not None:
        follower.status = str(job.error)
        return
    if job.result is None:  # cancelled
        return
    if not rerun.write(copy, job.prepared, job.result):
        _mark([name], force=True)  # the source changed again under it
        return
    follower.input, follower.result = job.prepared.source_coords, job.result
    if not job.prepared.notes:  # the next session's preview starts from here (a file saved now)
        follow_store.save_start(copy, job.prepared.plan.arrays)
    stats["finished"] += 1
    notes = job.prepared.notes
    follower.status = "Up to date" + (" (%s)" % "; ".join(notes) if notes else "")


def _tick():
    now = time.monotonic()
    for name, since in list(_dirty.items()):
        if now - since >= QUIET_SECONDS:
            del _dirty[name]
            _start(name)
        elif now - _previewed.get(name, 0.0) >= PREVIEW_SECONDS:
            _previewed[name] = now
            _live_preview(name)
    _poll()
    busy = _dirty or any(f.job is not None for f in _followers.values())
    return POLL_SECONDS if busy else None


def _poll():
    for name, follower in list(_followers.items()):
        if follower.job is not None and follower.job.done:
            _finish(name, follower)


def settle(timeout=None):
    """Follow every pending edit now (no quiet period) and wait for the exact results; for scripts
    and background mode, where no timer runs while a script does. True when all are written."""
    deadline = None if timeout is None else time.monotonic() + timeout
    for name in list(_dirty):
        del _dirty[name]
        _start(name)
    while True:
        jobs = [f.job for f in _followers.values() if f.job is not None]
        if not jobs:
            return True
        for job in jobs:
            job.wait(None if deadline is None else max(deadline - time.monotonic(), 0.0))
        _poll()
        if deadline is not None and time.monotonic() >= deadline:
            return not any(f.job is not None for f in _followers.values())


HANDLERS = (("depsgraph_update_post", _depsgraph_changed), ("frame_change_post", _frame_changed),
            ("undo_post", _undone), ("redo_post", _undone), ("load_post", _loaded))


def register():
    app_handlers.add(HANDLERS)
    schema.FOLLOW_EDITS_LISTENERS.append(switched)


def unregister():
    app_handlers.remove(HANDLERS)
    if switched in schema.FOLLOW_EDITS_LISTENERS:
        schema.FOLLOW_EDITS_LISTENERS.remove(switched)
    if bpy.app.timers.is_registered(_tick):
        bpy.app.timers.unregister(_tick)
    jobs = [f.job for f in _followers.values() if f.job is not None]
    for name in list(_followers):
        _drop(name)
    for job in jobs:  # cancelled: each ends at its next step; none outlives the add-on (or Blender's exit)
        job.wait(10.0)
