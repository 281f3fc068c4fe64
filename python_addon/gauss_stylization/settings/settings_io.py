"""Settings <-> plain dict (JSON), and the settings writer for scripts, scenes and tests.

The dict has one key per field of schema.OBJECT; "styles" is a list of slot
dicts (one key per field of schema.SLOT), custom normals are lists of 3 numbers.

The redo panel: when a live run is kept, the operator stores the settings it
ended with (to_json); if the artist then changes the iteration count in the
redo panel, Blender first undoes to the state *before* the run (older
settings) and calls execute(), which re-applies them (apply_json) so the redo
matches what was seen. Only json.loads is used: no eval.
"""

import json

from . import schema
from .fields import read_all, write_all
from .versioning import as_saved


def to_dict(settings):
    return read_all(schema.OBJECT, settings)


def to_json(settings):
    return json.dumps(to_dict(settings))


def apply_json(settings, text):
    """Every setting from to_json's text (KeyError if one is missing or unknown; text an earlier version
    wrote, without the settings added since, is read as it was written: versioning.as_saved)."""
    write_all(schema.OBJECT, settings, as_saved(json.loads(text)), complete=True)


def objects_to_json(objects):
    """The settings of the objects of a run: to_json's text for one object (the form a script
    passes), {"objects": {name: settings}} for several."""
    if len(objects) == 1:
        return to_json(objects[0].gauss_stylization)
    return json.dumps({"objects": {obj.name: to_dict(obj.gauss_stylization) for obj in objects}})


def apply_objects_json(objects, text):
    """Apply objects_to_json's text: one object's settings go to the first of ``objects``,
    named ones to the objects of those names (names not among ``objects`` are ignored). Text an
    earlier version wrote is read as it was written (versioning.as_saved)."""
    data = json.loads(text)
    if isinstance(data, dict) and set(data) == {"objects"}:
        by_name = {obj.name: obj for obj in objects}
        for name, settings in dict(data["objects"]).items():
            if name in by_name:
                write_all(schema.OBJECT, by_name[name].gauss_stylization, as_saved(settings), complete=True)
        return
    if objects:
        write_all(schema.OBJECT, objects[0].gauss_stylization, as_saved(data), complete=True)


def apply_dict(settings, data):
    """Set the settings named in ``data`` (the others keep their values).

    ``data["styles"]``, if given, replaces the slots by new ones made from its
    dicts, which may name only some fields (see add_slot). Unknown names raise KeyError.
    """
    data = dict(data)
    if "styles" in data:
        data["styles"] = [_named(spec) for spec in data["styles"]]
    write_all(schema.OBJECT, settings, data)


def add_slot(settings, spec):
    """Append a slot made from ``spec`` (field name -> value); fields it does not name keep
    their defaults, and a slot without a name is called after its preset. Returns the slot."""
    slot = settings.styles.add()
    write_all(schema.SLOT, slot, _named(spec))
    return slot


def _named(spec):
    if "name" in spec:
        return spec
    preset = spec.get("preset", schema.DEFAULT_PRESET)
    return dict(spec, name=schema.style_label(preset))
