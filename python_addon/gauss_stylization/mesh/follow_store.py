"""The recipe of a New Object copy, kept on the copy: what Follow Edits (run/follow.py) and Replay
re-run from the source's current shape.

The kept run's recipe (settings, vertex-group weights, changes during the run, step count: as
recipe_store.py keeps it for a mesh) and the topology it ran on, as JSON in a hidden ID property of
the copy, and the source object as an ID pointer property beside it, so a renamed source is still
found, and a deleted one reads as None. Both are undone and saved with the copy.
"""

import hashlib
import json

import numpy as np

from ..settings import schema
from . import recipe_store

KEY = schema.FOLLOW_RECIPE_KEY
SOURCE_KEY = "_gauss_follow_source"
VERSION = 1


def topology(arrays):
    """What identifies a mesh_io.MeshArrays' topology: its vertex and polygon counts and a digest of
    its corners (a run's recorded weights fit a mesh only with the same)."""
    digest = hashlib.sha1()
    for array in (arrays.corner_vertex, arrays.polygon_sides):
        digest.update(np.ascontiguousarray(array, np.int32).tobytes())
    return {"vertices": arrays.num_vertices, "polygons": arrays.num_polygons, "corners": digest.hexdigest()}


def fingerprint(arrays):
    """What identifies a stylized shape (a MeshArrays): its coordinates and topology. The shape a
    follower last solved has the fingerprint of the source's now when nothing changed."""
    digest = hashlib.sha1(np.ascontiguousarray(arrays.coords, np.float32).tobytes())
    digest.update(json.dumps(topology(arrays), sort_keys=True).encode())
    return digest.hexdigest()


def save(copy, source, run, arrays):
    """Keep on ``copy`` the recipe ``run`` (Session.recipe with its steps) made from ``source`` (an
    Object) whose stylized mesh was ``arrays`` (its rest shape kept too, and replaced by the source's
    shape at each exact re-run, save_start: the first edit's preview moves the copy by the source's
    change since)."""
    copy[KEY] = json.dumps({"version": VERSION, "run": run, "topology": topology(arrays),
                            "rest": recipe_store.pack(arrays.coords, np.float32),
                            "rest_fingerprint": fingerprint(arrays)}, separators=(",", ":"))
    copy[SOURCE_KEY] = source


def save_start(copy, arrays):
    """The copy was made again from the source shape ``arrays`` (same topology as the recipe's): the
    preview after the next edit (also in a later session) moves the copy by the source's change since."""
    stored = json.loads(copy[KEY])
    stored.update(rest=recipe_store.pack(arrays.coords, np.float32), rest_fingerprint=fingerprint(arrays))
    copy[KEY] = json.dumps(stored, separators=(",", ":"))


def has(obj):
    """Is ``obj`` a copy with a recipe? (A look-up only: the panel asks it at every redraw.)"""
    return KEY in obj.keys()


def load(copy):
    """(source Object or None when it was deleted, {"run", "topology"}), or None without a recipe."""
    text = copy.get(KEY)
    if not text:
        return None
    stored = json.loads(text)
    if stored.get("version") != VERSION:
        return None
    return source_of(copy), stored


def source_of(copy):
    """The copy's source Object, None when it was deleted (a look-up only)."""
    source = copy.get(SOURCE_KEY)
    try:
        # Deleted in the viewport, the pointer still holds it: an object in no collection is gone.
        if source is not None and not source.users_collection:
            source = None
    except ReferenceError:
        source = None
    return source


def forget(copy):
    """The copy's recipe removed (a later Mesh or Shape Key run on the copy writes where it cannot follow)."""
    for key in (KEY, SOURCE_KEY):
        if key in copy.keys():
            del copy[key]
