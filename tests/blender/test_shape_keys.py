"""Shape-key output and meshes that already have shape keys."""

import numpy as np

import helpers


def test_shape_key_output_blends_with_its_slider():
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    assert helpers.stylize(30, output='SHAPE_KEY') == {'FINISHED'}
    keys = obj.data.shape_keys.key_blocks
    assert [k.name for k in keys] == ["Basis", "Gauss Stylized"]
    assert np.array_equal(helpers.coords(obj), start)  # base mesh untouched
    stylized = helpers.key_coords(keys["Gauss Stylized"])
    assert np.abs(stylized - start).max() > 1e-2
    keys["Gauss Stylized"].value = 1.0
    np.testing.assert_allclose(helpers.evaluated_coords(obj), stylized, atol=1e-5)
    keys["Gauss Stylized"].value = 0.5
    np.testing.assert_allclose(helpers.evaluated_coords(obj), (start + stylized) / 2, atol=1e-5)
    keys["Gauss Stylized"].value = 0.0
    np.testing.assert_allclose(helpers.evaluated_coords(obj), start, atol=1e-6)


def _with_smile_key(obj):
    basis = obj.shape_key_add(name="Basis", from_mix=False)
    smile = obj.shape_key_add(name="Smile", from_mix=False)
    moved = helpers.key_coords(smile) + np.float32(0.25)
    smile.data.foreach_set("co", moved.reshape(-1))
    smile.value = 0.0
    obj.data.update()
    return basis, smile


def test_mesh_output_on_a_mesh_with_shape_keys_is_visible():
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    basis, smile = _with_smile_key(obj)
    smile_start = helpers.key_coords(smile)
    assert helpers.stylize(30, output='MESH') == {'FINISHED'}
    shown = helpers.evaluated_coords(obj)
    assert np.abs(shown - start).max() > 1e-2
    np.testing.assert_array_equal(helpers.key_coords(basis), shown)
    np.testing.assert_array_equal(helpers.key_coords(smile), smile_start)


def test_shape_key_output_on_a_mesh_with_shape_keys():
    obj = helpers.suzanne(levels=1)
    basis, smile = _with_smile_key(obj)
    basis_start, smile_start = helpers.key_coords(basis), helpers.key_coords(smile)
    assert helpers.stylize(30, output='SHAPE_KEY') == {'FINISHED'}
    keys = obj.data.shape_keys.key_blocks
    assert [k.name for k in keys] == ["Basis", "Smile", "Gauss Stylized"]
    np.testing.assert_array_equal(helpers.key_coords(basis), basis_start)
    np.testing.assert_array_equal(helpers.key_coords(smile), smile_start)
    stylized = helpers.key_coords(keys["Gauss Stylized"])
    np.testing.assert_allclose(helpers.evaluated_coords(obj), stylized, atol=1e-5)
    # Running again reuses the key instead of adding another one.
    assert helpers.stylize(5, output='SHAPE_KEY') == {'FINISHED'}
    assert [k.name for k in obj.data.shape_keys.key_blocks] == ["Basis", "Smile", "Gauss Stylized"]
