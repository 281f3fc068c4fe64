"""The recipe of a mesh's kept runs, kept in the .blend: what Replay (run/replay.py) re-runs.

A recipe is the rest shape (the coordinates the first of its runs started from) and, per kept run,
the settings and the vertex group weights it started with, every change made during it (settings,
repainted weights, pin targets a handle or a script set) at the step where it came, and its step
count. A run continues the recipe when it starts from exactly what the recipe's last run kept; any
other start (an edit of the mesh, a Shape Key run, which starts from the basis again) begins a new
recipe from that start.

Stored as one hidden ID property of the mesh (undone and saved with it): JSON, arrays as the base64
of their bytes, so that replayed values are the recorded ones bit for bit.
"""

import base64
import hashlib
import json

import numpy as np

KEY = "_gauss_recipe"
VERSION = 1


def pack(array, dtype):
    array = np.ascontiguousarray(array, dtype)
    return {"dtype": np.dtype(dtype).str, "shape": list(array.shape),
            "data": base64.b64encode(array.tobytes()).decode("ascii")}


def unpack(packed):
    data = base64.b64decode(packed["data"])
    return np.frombuffer(data, np.dtype(packed["dtype"])).reshape(packed["shape"]).copy()


def fingerprint(coords):
    """What identifies a run's float32 coordinates: a run continues the recipe when its start has the
    fingerprint of the last run's result."""
    return hashlib.sha1(np.ascontiguousarray(coords, np.float32).tobytes()).hexdigest()


def load(mesh):
    """The mesh's recipe as a dict ({"rest": packed, "runs": [...]}) or None."""
    text = mesh.get(KEY)
    if not text:
        return None
    recipe = json.loads(text)
    return recipe if recipe.get("version") == VERSION else None


def save(mesh, recipe):
    if recipe is None or not recipe["runs"]:
        if KEY in mesh:
            del mesh[KEY]
        return
    mesh[KEY] = json.dumps(recipe, separators=(",", ":"))


def add_run(mesh, start, run):
    """Add a kept run (a dict with "start_fingerprint" and "result_fingerprint") that started from
    ``start`` ((#V,3) float32): appended when it starts from what the last run kept, else the first run
    of a new recipe."""
    recipe = load(mesh)
    if recipe is None or recipe["runs"][-1]["result_fingerprint"] != run["start_fingerprint"]:
        recipe = {"version": VERSION, "rest": pack(start, np.float32), "runs": []}
    recipe["runs"].append(run)
    save(mesh, recipe)


def drop_last_run(mesh, result):
    """Reset put the mesh back where its last kept run started: that run leaves the recipe, if
    ``result`` ((#V,3) float32: what Reset found where the run wrote) is what the run kept."""
    recipe = load(mesh)
    if recipe is not None and recipe["runs"][-1]["result_fingerprint"] == fingerprint(result):
        recipe["runs"].pop()
        save(mesh, recipe)
