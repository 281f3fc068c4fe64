""".blend files store a style's preset as a number: files saved by earlier versions
must open with the same presets.

SAVED_NUMBERS is the record of what version 0.1.0 (before the settings schema)
wrote for each preset; it must never change. Presets the solver adds later get
the next numbers (the registry gauss_core.PRESETS only appends).
"""

import bpy
import numpy as np
import pytest

import helpers

SAVED_NUMBERS = {
    'CUBE': 0, 'TETRAHEDRON': 1, 'OCTAHEDRON': 2, 'DODECAHEDRON': 3, 'ICOSAHEDRON': 4,
    'SQUARE_PYRAMID': 5, 'TRUNCATED_PYRAMID': 6, 'TRIANGULAR_PRISM': 7, 'HEXAGONAL_PRISM': 8,
    'PLANE': 9, 'CYLINDER': 10, 'CONE': 11, 'DOUBLE_CONE': 12, 'CUSTOM': 99,
}


def _slots_with_every_preset():
    obj = helpers.uv_sphere(8, 4)
    for identifier in SAVED_NUMBERS:
        helpers.add_slot(obj, identifier, name=identifier)
    return obj


def _stored(obj):
    """The ID properties behind the add-on's registered properties, as the .blend holds them: since
    Blender 5.0 apart from the custom properties (bl_system_properties_get), before that among them."""
    return obj.bl_system_properties_get() if hasattr(obj, "bl_system_properties_get") else obj


def _stored_numbers(obj):
    """The numbers the .blend holds: the ID properties behind the enum."""
    return [slot["preset"] for slot in _stored(obj)["gauss_stylization"]["styles"]]


def test_presets_are_stored_with_the_numbers_of_saved_files():
    obj = _slots_with_every_preset()
    assert _stored_numbers(obj) == list(SAVED_NUMBERS.values())


def test_a_file_with_the_saved_numbers_opens_with_the_same_presets(tmp_path):
    obj = _slots_with_every_preset()
    # Write the numbers as an old file holds them, in an order unlike the registry's.
    shuffled = list(reversed(SAVED_NUMBERS.items()))
    for raw, (identifier, number) in zip(_stored(obj)["gauss_stylization"]["styles"], shuffled):
        raw["name"], raw["preset"] = identifier, number
    path = str(tmp_path / "saved_presets.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)
    slots = bpy.data.objects["Sphere"].gauss_stylization.styles
    assert [(slot.name, slot.preset) for slot in slots] == [(name, name) for name, _ in shuffled]


def test_a_preset_number_this_version_does_not_know_is_refused_by_name():
    # E.g. a file saved by a later version whose solver has more presets.
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE', name="Later")
    _stored(obj)["gauss_stylization"]["styles"][0]["preset"] = 50
    before = helpers.coords(obj)
    with pytest.raises(RuntimeError, match="Style 'Later': Style holds a value this version does not know"):
        bpy.ops.object.gauss_stylize(iterations=3)
    assert np.array_equal(helpers.coords(obj), before)
