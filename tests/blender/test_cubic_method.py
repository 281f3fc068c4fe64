"""The cubic method in the add-on: switching it during a live run, what the panel shows, and the
scripted operator with it."""

import bpy
import numpy as np

import helpers
from test_schema import _Layout  # records the rows a panel draws


def _session(addon, obj):
    addon.run.session.ensure_style_slot(obj.gauss_stylization)
    return addon.run.session.Session(obj)


def _run(addon, obj, switch_at=None, switch_to=None, steps=6):
    """Steps of a live run; at step ``switch_at`` the panel's Method becomes ``switch_to``."""
    run = _session(addon, obj)
    factorizations = run.solver.factorization_count
    for step in range(steps):
        if step == switch_at:
            obj.gauss_stylization.method = switch_to
            assert run.sync_settings() is None
            assert run.solver.method == switch_to.lower()
            assert run.solver.factorization_count == factorizations  # no new set-up
        run.step()
    result = run.result.copy()
    run.cancel()
    return result


def test_switching_method_mid_run_takes_effect_at_the_next_step(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    gauss = _run(addon, obj)
    switched = _run(addon, obj, switch_at=3, switch_to='CUBIC')
    assert np.array_equal(helpers.coords(obj), start)  # each cancel restored the mesh exactly
    obj.gauss_stylization.method = 'CUBIC'
    cubic = _run(addon, obj)
    back = _run(addon, obj, switch_at=3, switch_to='GAUSS')
    for a, b in ((gauss, switched), (cubic, switched), (cubic, back), (gauss, back)):
        assert not np.array_equal(a, b)
    # The first three steps of a switched run are those of the method it started with.
    obj.gauss_stylization.method = 'GAUSS'
    assert np.array_equal(_run(addon, obj, steps=3), _run(addon, obj, switch_at=3, switch_to='CUBIC', steps=3))


def test_cubic_keeps_everything_else_of_the_run(addon):
    # Pins, a region with its own strength and rotation, shape-key output, keep and Reset.
    obj = helpers.uv_sphere(32, 16)
    start = helpers.coords(obj)
    pinned = np.flatnonzero(start[:, 2] < -0.9)
    helpers.add_group(obj, "Feet", pinned)
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > 0.3))
    settings = obj.gauss_stylization
    addon.settings_io.apply_dict(settings, dict(method='CUBIC', cubic_lambda=0.4, pin_group="Feet",
                                                output='SHAPE_KEY', uncovered='UNSTYLED'))
    helpers.add_slot(obj, 'DODECAHEDRON', "Top", mu=2.0, orientation=(0.0, 0.0, 0.4))
    assert helpers.stylize(60) == {'FINISHED'}
    key = obj.data.shape_keys.key_blocks["Gauss Stylized"]
    result = helpers.key_coords(key)
    assert np.array_equal(result[pinned], start[pinned])
    tris = helpers.triangles(obj)[0]
    in_top = (start[tris][:, :, 2] > 0.3).all(axis=1)
    turn = np.array(obj.gauss_stylization.styles[0].orientation.to_matrix())
    turned_axes = helpers.AXES @ turn.T
    assert (helpers.aligned_share(obj, turned_axes, positions=result, triangle_mask=in_top)
            > helpers.aligned_share(obj, turned_axes, positions=start, triangle_mask=in_top) + 0.2)
    below = start[:, 2] < -0.2  # unstyled and far from the styled region: barely moved
    assert np.abs(result[below] - start[below]).max() < 0.1
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert np.array_equal(helpers.key_coords(obj.data.shape_keys.key_blocks["Gauss Stylized"]), start)


def test_the_panel_shows_cubic_lambda_only_for_cubic(addon):
    obj = helpers.suzanne(levels=0)
    rows = []
    layout = _Layout(rows)
    panel = addon.settings.fields.Panel.METHOD
    addon.view.sidebar.draw_rows(layout, obj, obj.gauss_stylization, addon.settings.schema.OBJECT, panel)
    assert rows == ["method"]
    obj.gauss_stylization.method = 'CUBIC'
    rows.clear()
    addon.view.sidebar.draw_rows(layout, obj, obj.gauss_stylization, addon.settings.schema.OBJECT, panel)
    assert rows == ["method", "cubic_lambda"]
    rows.clear()
    addon.view.sidebar.draw_rows(layout, obj, obj.gauss_stylization, addon.settings.schema.OBJECT,
                                 addon.settings.fields.Panel.SOLVER)
    # Lambda and ADMM Iterations are the Gauss method's; Resolution Independent, Square Flat Regions and
    # the Proxy Threshold act on both methods.
    assert rows == ["tolerance", "iterations", "proxy_threshold", "keep_volume", "avoid_self_intersections",
                    "resolution_independent", "square_flat_regions"]

