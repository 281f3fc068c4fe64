"""Settings <-> plain dict (JSON), for the redo panel.

When a live run is kept, the operator stores the settings it ended with; if
the artist then changes the iteration count in the redo panel, Blender first
undoes to the state *before* the run (older settings) and calls execute(),
which re-applies these settings so the redo matches what was seen.
Only json.loads is used: no eval.
"""

import json

SLOT_FIELDS = ("name", "preset", "sigma", "mu", "axis_contribution", "vertex_group")
SETTINGS_FIELDS = ("lam", "admm_iterations", "output", "pin_group", "uncovered", "active_style_index")


def to_json(settings):
    data = {field: getattr(settings, field) for field in SETTINGS_FIELDS}
    data["styles"] = [_slot_to_dict(slot) for slot in settings.styles]
    return json.dumps(data)


def _slot_to_dict(slot):
    data = {field: getattr(slot, field) for field in SLOT_FIELDS}
    data["orientation"] = list(slot.orientation)
    data["custom_normals"] = slot.custom_normal_list()
    return data


def apply_json(settings, text):
    data = json.loads(text)
    for field in SETTINGS_FIELDS:
        setattr(settings, field, data[field])
    settings.styles.clear()
    for slot_data in data["styles"]:
        slot = settings.styles.add()
        for field in SLOT_FIELDS:
            setattr(slot, field, slot_data[field])
        slot.orientation = slot_data["orientation"]
        slot.set_custom_normals(slot_data["custom_normals"])
