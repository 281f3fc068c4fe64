"""Reset restores exactly; settings and the Reset data survive save + reopen."""

import math

import bpy
import numpy as np
import pytest

import helpers


def test_reset_restores_exactly():
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    assert not bpy.ops.object.gauss_stylize_reset.poll()
    helpers.stylize(25)
    assert not np.array_equal(helpers.coords(obj), start)
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert np.array_equal(helpers.coords(obj), start)


def test_reset_of_shape_key_output():
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    helpers.stylize(25, output='SHAPE_KEY')
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    key = obj.data.shape_keys.key_blocks["Gauss Stylized"]
    assert np.array_equal(helpers.key_coords(key), start)
    assert np.array_equal(helpers.coords(obj), start)


def _configure(obj):
    settings = obj.gauss_stylization
    helpers.add_group(obj, "Pins", [0, 1, 2])
    helpers.add_group(obj, "Top", range(10, 200))
    settings.lam = 6.5
    settings.admm_iterations = 3
    settings.iterations = 12
    settings.output = 'SHAPE_KEY'
    settings.pin_group = "Pins"
    settings.uncovered = 'UNSTYLED'
    helpers.add_slot(obj, 'SQUARE_PYRAMID', "", name="Base", sigma=7.0, mu=2.0,
                     orientation=(0.1, 0.2, 0.3), axis_contribution=0.25)
    custom = helpers.add_slot(obj, 'CUSTOM', "Top", name="Mine")
    custom.set_custom_normals([(0, 0, 1), (1, 0, 0), (0, 1, 1)])
    settings.active_style_index = 1


def test_settings_and_reset_data_survive_save_and_reopen(tmp_path):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    _configure(obj)
    assert helpers.stylize(10) == {'FINISHED'}
    stylized = helpers.key_coords(obj.data.shape_keys.key_blocks["Gauss Stylized"])
    path = str(tmp_path / "scene.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=path, load_ui=False)

    obj = bpy.data.objects["Suzanne"]
    settings = obj.gauss_stylization
    assert (settings.lam, settings.admm_iterations, settings.iterations) == (6.5, 3, 12)
    assert (settings.output, settings.pin_group, settings.uncovered) == ('SHAPE_KEY', "Pins", 'UNSTYLED')
    assert settings.active_style_index == 1
    base, mine = settings.styles
    assert (base.name, base.preset, base.sigma, base.mu, base.vertex_group) == ("Base", 'SQUARE_PYRAMID', 7.0, 2.0, "")
    assert base.axis_contribution == 0.25
    assert [round(a, 5) for a in base.orientation] == [0.1, 0.2, 0.3]
    assert (mine.name, mine.preset, mine.vertex_group) == ("Mine", 'CUSTOM', "Top")
    assert mine.custom_normal_list() == [(0, 0, 1), (1, 0, 0), (0, 1, 1)]
    key = obj.data.shape_keys.key_blocks["Gauss Stylized"]
    assert np.array_equal(helpers.key_coords(key), stylized)

    helpers.activate(obj)
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert np.array_equal(helpers.key_coords(key), start)
    assert helpers.stylize(3) == {'FINISHED'}  # the reopened settings run


def test_custom_normals_from_a_script_are_checked():
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, 'CUSTOM')
    slot.set_custom_normals([(0, 0, 1), [1.0, 0.0, 0.0]])
    for bad in ([(0, 0, 0)], [(0, 0)], [(math.nan, 0, 1)], ["abc"]):
        with pytest.raises((ValueError, TypeError)):
            slot.set_custom_normals(bad)
        assert slot.custom_normal_list() == [(0, 0, 1), (1, 0, 0)]  # unchanged
