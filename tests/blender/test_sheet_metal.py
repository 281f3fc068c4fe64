"""Sheet Metal in the add-on (docs/styles.md#sheet-metal): a slot's style like any other. A slot takes the
style's own Sigma, the style unbends a mesh at the Lambda its tooltip names, and it works with Regions,
painted strength, pins, every output and bakes."""
import json

import bpy
import numpy as np
import pytest

import helpers
import rig
from measures import developability
from panel_recorder import draw, labels


def _sheet_suzanne(addon, **slot_values):
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'SHEET_METAL', **slot_values)
    return obj, addon.settings.schema.LOOK_LAMBDA["sheet_metal"]


def _developability(obj, co=None):
    tris, _ = helpers.triangles(obj)
    return developability(helpers.coords(obj) if co is None else co, tris)


def test_a_slot_takes_sheet_metals_own_sigma_and_gives_it_back(addon):
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, 'CUBE')
    plain = slot.sigma
    own = addon.native.preset_strengths()["sheet_metal"][0]
    assert own != plain
    slot.preset = 'SHEET_METAL'
    assert slot.sigma == own and slot.name == "Sheet Metal"
    slot.preset = 'TETRAHEDRON'
    assert slot.sigma == plain
    slot.sigma = 7.0  # the artist's own: kept whatever the style
    slot.preset = 'SHEET_METAL'
    assert slot.sigma == 7.0
    slot.preset = 'CUSTOM'
    assert slot.sigma == 7.0


def test_it_unbends_a_mesh_at_the_lambda_its_tooltip_names(addon):
    obj, look = _sheet_suzanne(addon)
    item = next(i for i in addon.settings.schema._preset_items() if i[0] == 'SHEET_METAL')
    assert "Lambda about %g" % look in item[2] and "Sigma %g" % obj.gauss_stylization.styles[0].sigma in item[2]
    before = _developability(obj)
    assert helpers.stylize(100, lam=look) == {'FINISHED'}
    after = _developability(obj)
    co = helpers.coords(obj)
    assert np.isfinite(co).all() and after < before / 2, (before, after)


def test_the_sidebar_says_where_it_shows_while_lambda_is_far_below(addon):
    obj, look = _sheet_suzanne(addon)
    helpers.activate(obj)
    hint = "Sheet Metal shows from Lambda about %g (Solver panel)" % look

    def shown():
        return " ".join(labels(draw(addon.ui.VIEW3D_PT_gauss_styles)))

    obj.gauss_stylization.lam = 4.0
    assert hint in shown()
    obj.gauss_stylization.lam = look
    assert hint not in shown()
    obj.gauss_stylization.lam = 4.0
    obj.gauss_stylization.styles[0].preset = 'CUBE'
    assert "shows from Lambda" not in shown()


def test_a_region_keeps_it_to_its_faces(addon):
    obj, look = _sheet_suzanne(addon)
    rest = helpers.coords(obj)
    helpers.add_group(obj, "Right", np.flatnonzero(rest[:, 0] > 0.0))
    obj.gauss_stylization.styles[0].vertex_group = "Right"
    assert helpers.stylize(60, lam=look) == {'FINISHED'}
    co = helpers.coords(obj)
    tris, _ = helpers.triangles(obj)
    side = rest[tris].mean(axis=1)[:, 0]
    right, left = tris[side > 0.2], tris[side < -0.2]  # away from the Region's border
    assert developability(co, right) < 0.5 * developability(rest, right)
    assert developability(co, left) > 0.8 * developability(rest, left)


def test_painted_strength_scales_it(addon):
    results = []
    for weight in (1.0, 0.3):
        helpers.clear_scene()
        obj, look = _sheet_suzanne(addon)
        rest = helpers.coords(obj)
        helpers.add_group(obj, "Paint", range(len(rest)), weight)
        obj.gauss_stylization.styles[0].vertex_group = "Paint"
        assert helpers.stylize(60, lam=look) == {'FINISHED'}
        results.append(np.linalg.norm(helpers.coords(obj) - rest, axis=1).mean())
    assert results[1] < 0.8 * results[0], results


def test_pinned_vertices_stay_where_they_are(addon):
    obj, look = _sheet_suzanne(addon)
    rest = helpers.coords(obj)
    top = np.flatnonzero(rest[:, 2] > 0.5)
    helpers.add_group(obj, "Top", top)
    assert helpers.stylize(60, lam=look, pin_group="Top") == {'FINISHED'}
    co = helpers.coords(obj)
    assert np.array_equal(co[top], rest[top])
    assert np.linalg.norm(co - rest, axis=1).max() > 1e-2


def test_moved_handles_carry_it_along(addon):
    obj, look = _sheet_suzanne(addon)
    rest = helpers.coords(obj)
    pins = np.flatnonzero(np.abs(rest[:, 0]) > 1.0)  # the ears' tips
    helpers.add_group(obj, "Ears", pins)
    obj.gauss_stylization.pin_group = "Ears"
    obj.gauss_stylization.lam = look
    targets = rest[pins].astype(np.float64)
    targets[:, 2] += 0.4  # both ears' handles lifted
    helpers.activate(obj)
    assert bpy.ops.object.gauss_stylize(iterations=60, pin_targets=json.dumps({obj.name: targets.tolist()})) \
        == {'FINISHED'}
    co = helpers.coords(obj)
    assert np.allclose(co[pins], targets.astype(np.float32), atol=1e-6)
    near = (np.abs(rest[:, 0]) > 0.8) & (np.abs(rest[:, 0]) <= 1.0)
    assert (co[near, 2] - rest[near, 2]).mean() > 0.1  # the ears followed their handles
    tris, _ = helpers.triangles(obj)
    assert developability(co, tris) < developability(rest, tris)


@pytest.mark.parametrize("output", ['SHAPE_KEY', 'NEW_OBJECT'])
def test_every_output_gets_the_same_result(addon, output):
    obj, look = _sheet_suzanne(addon)
    assert helpers.stylize(40, lam=look) == {'FINISHED'}
    expected = helpers.coords(obj)
    helpers.clear_scene()
    obj, _ = _sheet_suzanne(addon)
    rest = helpers.coords(obj)
    assert helpers.stylize(40, lam=look, output=output) == {'FINISHED'}
    if output == 'SHAPE_KEY':
        got = helpers.key_coords(obj.data.shape_keys.key_blocks["Gauss Stylized"])
        assert np.array_equal(helpers.coords(obj), rest)
    else:
        got = helpers.coords(bpy.context.active_object)
    assert np.array_equal(got, expected)


def test_a_bake_unbends_every_frame(addon, tmp_path):
    obj = rig.bent_capsule()
    helpers.add_slot(obj, 'SHEET_METAL')
    obj.gauss_stylization.lam = addon.settings.schema.LOOK_LAMBDA["sheet_metal"]
    path = tmp_path / "capsule.pc2"
    assert bpy.ops.object.gauss_bake_animation(frame_start=1, frame_end=4, filepath=str(path),
                                               warm_start=True) == {'FINISHED'}
    cache = addon.pc2.read(str(path))
    tris, _ = helpers.triangles(obj)
    addon.mesh.cache_modifier.find(obj).show_viewport = False  # the animation itself, not the bake
    for frame in (1, 4):
        shown = rig.shown_at(obj, frame)
        baked = cache.frames[frame - 1]
        assert np.isfinite(baked).all()
        assert developability(baked, tris) < 0.75 * developability(shown, tris), frame
