"""Replay: the mesh's recipe (mesh/recipe_store.py) run again from its rest shape, every kept run in
order, each through a Session as the run was made: the settings and weights it started with, each
recorded change at its step, its step count, then keep. The replayed runs record themselves, so the
recipe afterwards is the one replayed.

With the Mesh output the rest shape is written back first; with the Shape Key output the runs start
from the basis as it is now, so a basis edited since follows. The copy a New Object run kept is
made again from its source as the source is now (rerun.py), as Follow Edits makes it. Scripts may call ``replay(obj)`` or
read the recipe with ``recipe(obj)``.
"""

from ..errors import SettingsError
from ..mesh import follow_store, mesh_io, output, recipe_store
from ..settings.settings_io import apply_dict, to_dict
from ..settings.versioning import as_recorded, bring_stamped_up_to_date
from . import rerun
from .session import Plan, Session


def recipe(obj):
    """The recipe of ``obj``'s mesh: {"rest": (#V,3) float32, "runs": [{"settings", "steps", "events",
    ...}]}, or None when it has none."""
    stored = recipe_store.load(obj.data)
    if stored is None:
        return None
    return dict(stored, rest=recipe_store.unpack(stored["rest"]))


def problem(obj):
    """Why ``obj`` cannot be replayed (None if it can). A look-up only: the operator's poll asks it at
    every redraw of the sidebar, and a recipe may be megabytes of JSON (replay() reads it)."""
    if follow_store.has(obj):
        return rerun.problem(obj)
    if recipe_store.KEY not in obj.data:
        return "'%s' has no kept run to replay (Replay follows kept runs with Output Mesh or Shape Key)" % obj.name
    return None


def replay(obj, progress=None):
    """Re-run ``obj``'s recipe; returns (runs, steps) replayed. progress(fraction) is called after each
    step. Raises SettingsError if it cannot (the object's settings are back as they were)."""
    why = problem(obj)
    if why is not None:
        raise SettingsError(why)
    if follow_store.has(obj):  # a New Object copy: its run again from the source as it is now
        _notes, steps = rerun.replay_copy(obj)
        if progress is not None:
            progress(1.0)
        return 1, steps
    mesh = obj.data
    stored = recipe_store.load(mesh)
    if stored is None or len(mesh.vertices) != len(recipe_store.unpack(stored["rest"])):
        raise SettingsError("The mesh's vertex count changed since its runs were kept (or its recipe is "
                            "from another version); they cannot be replayed")
    runs = stored["runs"]
    settings = obj.gauss_stylization
    # Before the snapshot the end restores: Plan would bring a stamped object up to date under it, and
    # restoring a snapshot taken earlier would then write today's value over the old rule for good.
    bring_stamped_up_to_date(settings)
    before, kept = to_dict(settings), _snapshot(obj)
    if runs[0]["output"] == output.MeshTarget.kind:
        mesh_io.write_vertex_coords(mesh, recipe_store.unpack(stored["rest"]))
        base = mesh_io.base_key(mesh)
        if base is not None:
            mesh_io.write_key_coords(base, recipe_store.unpack(stored["rest"]))
        mesh_io.tag_changed(mesh)
    recipe_store.save(mesh, None)
    total, done = max(sum(run["steps"] for run in runs), 1), 0
    try:
        for run in runs:
            apply_dict(settings, dict(as_recorded(run["settings"]), output=run["output"]))
            weights = {group: recipe_store.unpack(w) for group, w in run["weights"].items()}
            session = Session(Plan(obj, weights=weights))
            events = {}
            for event in run["events"]:
                events.setdefault(event["step"], []).append(event)
            try:
                for step in range(run["steps"]):
                    for event in events.get(step, ()):
                        session.replay_event(event)
                    session.step()
                    done += 1
                    if progress is not None:
                        progress(done / total)
            except BaseException:
                session.cancel()
                raise
            session.keep()
    except BaseException:  # nothing the artist had is lost: the mesh and its recipe as they were
        _restore(obj, kept)
        recipe_store.save(mesh, stored)
        raise
    finally:
        apply_dict(settings, before)
    return len(runs), done


def _snapshot(obj):
    """The mesh's coordinates and those of every shape key (what a replay writes)."""
    keys = obj.data.shape_keys
    blocks = keys.key_blocks if keys is not None else ()
    return mesh_io.read_vertex_coords(obj.data), [(k.name, mesh_io.read_key_coords(k)) for k in blocks]


def _restore(obj, kept):
    coords, keys = kept
    mesh_io.write_vertex_coords(obj.data, coords)
    for name, values in keys:
        mesh_io.write_key_coords(obj.data.shape_keys.key_blocks[name], values)
    mesh_io.tag_changed(obj.data)
