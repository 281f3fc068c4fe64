"""Painted strength: a style slot's Region weights scale its mu per face (the mean of the face's
vertex weights), overlapping Regions blend, and a live run picks up Weight Paint strokes when the
artist returns to Object Mode."""

import bpy
import numpy as np
import pytest

import helpers

CUBE = np.vstack([np.eye(3), -np.eye(3)])


def _session(addon, obj):
    addon.run.session.ensure_style_slot(obj.gauss_stylization)
    return addon.run.session.Session(obj)


def _result(addon, obj, steps):
    run = _session(addon, obj)
    run.step(steps)
    out = helpers.coords(obj)
    run.cancel()
    return out


def _painted_sphere(weights_of, name="Paint"):
    """A UV sphere with a group whose weight at each vertex is weights_of(coords), style slot 0's
    Region, and Other Faces unstyled."""
    obj = helpers.uv_sphere()
    start = helpers.coords(obj)
    group = obj.vertex_groups.new(name=name)
    for index, weight in enumerate(weights_of(start)):
        group.add([index], float(weight), 'REPLACE')
    settings = obj.gauss_stylization
    settings.uncovered = 'UNSTYLED'
    helpers.add_slot(obj, 'CUBE', name)
    return obj, start


def test_a_region_of_weight_one_is_the_whole_mesh_bit_for_bit(addon):
    # One object (two separately built spheres can differ in their last bits), with and without the Region.
    obj, _ = _painted_sphere(lambda co: np.ones(len(co)))
    slot = obj.gauss_stylization.styles[0]
    for method in ('GAUSS', 'CUBIC'):
        obj.gauss_stylization.method = method
        slot.vertex_group = "Paint"
        painted = _result(addon, obj, 8)
        slot.vertex_group = ""
        np.testing.assert_array_equal(painted, _result(addon, obj, 8))


def test_a_weight_of_a_half_is_the_curves_share_of_the_mu(addon):
    # The paint curve (settings/paint_curve.py) turns a painted 0.5 into a mu scale of about 0.1 with the
    # Gauss method at Lambda 4 and Resolution Independent (0.07 without it, and with the curve an object
    # saved under settings version 3 keeps), and leaves it 0.5 with the Cubic method.
    obj, _ = _painted_sphere(lambda co: np.full(len(co), 0.5))
    settings = obj.gauss_stylization
    slot = settings.styles[0]
    curve = addon.settings.paint_curve
    settings.lam = 4.0
    cases = (('GAUSS', True, False, (0.09, 0.11)), ('GAUSS', False, False, (0.06, 0.08)),
             ('GAUSS', True, True, (0.06, 0.08)), ('CUBIC', True, False, (0.5, 0.5)))
    for method, independent, old_curve, expected in cases:
        settings.method, settings.resolution_independent, settings.old_paint_curve = method, independent, old_curve
        scale = float(curve.strength([0.5], curve.steepness_of(settings))[0])
        assert expected[0] <= scale <= expected[1], (method, independent, old_curve, scale)
        slot.vertex_group, slot.mu = "Paint", 1.0
        half = _result(addon, obj, 8)
        slot.vertex_group, slot.mu = "", scale
        np.testing.assert_array_equal(half, _result(addon, obj, 8))


def test_the_curve_follows_lambda_mid_run(addon):
    # A live change of Lambda changes the curve's steepness: the face weights are given anew.
    obj, _ = _painted_sphere(lambda co: np.full(len(co), 0.5))
    obj.gauss_stylization.lam = 4.0
    run = _session(addon, obj)
    try:
        run.step(1)
        before = run.plan.paint_steepness
        obj.gauss_stylization.lam = 8.0
        assert run.sync_settings() is None
        assert run.plan.paint_steepness > before
        curve = addon.settings.paint_curve
        eight = curve.steepness('GAUSS', 8.0, curve.PULL_SHOWN_INDEPENDENT)
        np.testing.assert_allclose(run.plan.regions_for(obj.gauss_stylization)[0][:, 0],
                                   curve.strength([0.5], eight)[0], rtol=1e-6)
        # So do a change of Resolution Independent, which moves where the style starts to show, and of the
        # old curve's switch: the run's weights (made when the change reached it) follow each.
        for independent, old_curve, pull in ((False, False, curve.PULL_SHOWN), (True, True, curve.PULL_SHOWN),
                                             (True, False, curve.PULL_SHOWN_INDEPENDENT)):
            obj.gauss_stylization.resolution_independent = independent
            obj.gauss_stylization.old_paint_curve = old_curve
            assert run.sync_settings() is None
            assert run.plan.paint_steepness == curve.steepness('GAUSS', 8.0, pull), (independent, old_curve)
    finally:
        run.cancel()


def test_weights_are_read_from_the_group_and_zero_leaves_faces_unstyled(addon):
    # Weight 0 below the equator, rising to 1 at the top: polygons whose vertices all weigh 0 have
    # no style; those whose corners mostly carry a weight, the mean of those corners' weights
    # through the paint curve.
    obj, start = _painted_sphere(lambda co: np.clip(co[:, 2], 0.0, 1.0))
    plan = addon.run.session.Plan(obj)
    try:
        face_w, vertex_w = plan.regions
        assert vertex_w is None  # the cubic method takes its vertices' strength from their faces
        arrays = plan.arrays
        expected = np.clip(start[:, 2], 0, 1)
        painted = arrays.polygon_average((expected > 0).astype(float))
        polygon_mean = np.where(painted > 0.5, arrays.polygon_average(expected) / np.maximum(painted, 1e-30),
                                0.0)[arrays.tri_polygon]
        np.testing.assert_allclose(face_w[:, 0],
                                   addon.settings.paint_curve.strength(polygon_mean, plan.paint_steepness),
                                   atol=1e-6)
        below = polygon_mean == 0
        assert below.sum() > len(below) // 3 and np.all(face_w[below] == 0)
    finally:
        plan.release()
    result = _result(addon, obj, 30)
    tri = helpers.triangles(obj)[0]
    centre_z = start[tri].mean(axis=1)[:, 2]
    low, high = centre_z < -0.2, centre_z > 0.6
    # The unstyled lower part barely changes (ARAP pulled by the top only); the top stylizes.
    assert helpers.aligned_share(obj, CUBE, result, high) > helpers.aligned_share(obj, CUBE, start, high) + 0.2
    assert abs(helpers.aligned_share(obj, CUBE, result, low) - helpers.aligned_share(obj, CUBE, start, low)) < 0.1


def test_overlapping_regions_blend(addon):
    # Two slots whose Regions both cover the sphere with weight 1: the second a cube turned about z.
    # The result lies between the two styles on their own: overlapping Regions add up, neither slot wins.
    turned = np.array([[np.cos(np.pi / 4), -np.sin(np.pi / 4), 0], [np.sin(np.pi / 4), np.cos(np.pi / 4), 0],
                       [0, 0, 1]])
    turned_cube = np.vstack([turned.T, -turned.T])
    obj, start = _painted_sphere(lambda co: np.ones(len(co)), "A")
    helpers.add_group(obj, "B", range(len(start)))
    second = helpers.add_slot(obj, 'CUBE', "B")
    second.orientation = (0.0, 0.0, np.pi / 4)
    helpers.add_group(obj, "Unused", [])
    slots = obj.gauss_stylization.styles
    blend = _result(addon, obj, 30)
    slots[1].vertex_group = "Unused"
    first_only = _result(addon, obj, 30)
    slots[0].vertex_group, slots[1].vertex_group = "Unused", "B"
    turned_only = _result(addon, obj, 30)

    def shares(result):
        return helpers.aligned_share(obj, CUBE, result), helpers.aligned_share(obj, turned_cube, result)
    (blend_first, blend_turned), (first, first_turned), (turned_first, turned) = map(
        shares, (blend, first_only, turned_only))
    assert turned_first + 0.05 < blend_first < first - 0.05
    assert first_turned + 0.05 < blend_turned < turned - 0.05


def test_returning_from_weight_paint_picks_up_new_weights(addon):
    obj, start = _painted_sphere(lambda co: np.zeros(len(co)))
    run = _session(addon, obj)
    try:
        run.step(5)
        assert helpers.aligned_share(obj, CUBE) < helpers.aligned_share(obj, CUBE, start) + 0.02
        bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
        obj.vertex_groups["Paint"].add(list(range(len(start))), 1.0, 'REPLACE')  # the strokes
        assert run.sync_settings() is None
        run.step(2)
        assert not np.any(run.weights["Paint"])  # still painting: not read yet
        bpy.ops.object.mode_set(mode='OBJECT')
        assert run.sync_settings() is None
        np.testing.assert_array_equal(run.weights["Paint"], 1.0)
        assert not run.converged
        run.step(25)
        assert helpers.aligned_share(obj, CUBE) > helpers.aligned_share(obj, CUBE, start) + 0.2
    finally:
        if bpy.context.object is not None and bpy.context.object.mode != 'OBJECT':
            bpy.ops.object.mode_set(mode='OBJECT')
        run.cancel()


def test_a_live_run_holds_the_object_still_while_its_weights_are_painted(addon):
    obj, start = _painted_sphere(lambda co: np.ones(len(co)))
    live = helpers.live_run([obj])
    try:
        live.tick()
        live.tick()
        bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
        held = helpers.coords(obj)
        assert live.tick().stepped == 0 and np.array_equal(helpers.coords(obj), held)
        bpy.ops.object.mode_set(mode='OBJECT')
        assert live.tick().stepped == 1 and not np.array_equal(helpers.coords(obj), held)
    finally:
        if obj.mode != 'OBJECT':
            bpy.ops.object.mode_set(mode='OBJECT')
        live.cancel()


@pytest.mark.parametrize("uncovered", ['FIRST_SLOT', 'UNSTYLED'])
def test_regions_of_weight_one_take_exactly_the_faces_they_took_before(addon, uncovered):
    # Weights of 1 on part of the mesh: every triangle's weights are 1 for the slot it had before
    # (styles.face_styles, the assignment before weights) and 0 for the others; set_face_weights
    # steps such weights bit for bit as set_face_styles (tests/cpp/test_face_weights.cpp).
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > 0.1))
    helpers.add_group(obj, "Left", np.flatnonzero(start[:, 0] < -0.2))
    helpers.add_slot(obj, 'CUBE')
    helpers.add_slot(obj, 'CUBE', group="Top")
    helpers.add_slot(obj, 'OCTAHEDRON', group="Left")
    obj.gauss_stylization.uncovered = uncovered
    plan = addon.run.session.Plan(obj)
    try:
        weights = plan.regions[0]
        groups = [slot.vertex_group for slot in obj.gauss_stylization.styles]
        old = addon.settings.styles.face_styles(plan.arrays, plan.weights, groups, uncovered)
    finally:
        plan.release()
    overlap = (weights > 0).sum(axis=1) > 1  # where Top and Left overlap the weights now blend
    one_hot = np.zeros_like(weights)
    one_hot[old >= 0, old[old >= 0]] = 1.0
    assert overlap.any() and (~overlap).sum() > len(overlap) // 2
    np.testing.assert_array_equal(weights[~overlap], one_hot[~overlap])


OLD_CURVE = "old_paint_curve"


def _half_painted(name, independent=True):
    obj, _ = _painted_sphere(lambda co: np.full(len(co), 0.5))
    obj.name = name
    obj.gauss_stylization.resolution_independent = independent
    return obj


def test_objects_saved_under_version_3_keep_its_curve(addon, tmp_path):
    """A file saved at settings version 3 (Resolution Independent on, the paint curve's onset then the
    same as without it) opens with that curve and stylizes as it did; new objects get today's."""
    versioning = addon.settings.versioning
    field = addon.settings.schema.field(addon.settings.schema.OBJECT, OLD_CURVE)
    assert field.since == 4 <= versioning.VERSION
    obj = _half_painted("Old")
    _half_painted("Off", independent=False)
    assert obj.gauss_stylization.old_paint_curve is False
    results = {}
    for curve in (True, False):
        obj.gauss_stylization.old_paint_curve = curve
        results[curve] = _result(addon, obj, 8)
    assert not np.array_equal(results[True], results[False])
    helpers.save_as_version(addon, str(tmp_path / "v3.blend"), 3, OLD_CURVE)
    helpers.clear_scene()
    bpy.ops.wm.open_mainfile(filepath=str(tmp_path / "v3.blend"), load_ui=False)
    obj = bpy.data.objects["Old"]
    assert obj.gauss_stylization.old_paint_curve is True
    np.testing.assert_array_equal(_result(addon, obj, 8), results[True])
    # Without Resolution Independent the curve did not change: nothing is written out there.
    assert bpy.data.objects["Off"].gauss_stylization.old_paint_curve is False
    # The Styles panel shows the old curve where it is in effect, so that the artist can untick it.
    assert field.panel is addon.settings.fields.Panel.STYLES and field.shown(obj.gauss_stylization)
    # The cubic method does not read it: the row is not shown there.
    obj.gauss_stylization.method = addon.settings.schema.CUBIC
    assert not field.shown(obj.gauss_stylization)
    fresh = _half_painted("New")
    assert fresh.gauss_stylization.old_paint_curve is False and not field.shown(fresh.gauss_stylization)


def test_a_recipe_recorded_under_version_3_replays_with_its_curve(addon):
    """Replay of a run whose recipe predates the field uses the curve it ran with, whatever the object
    says now."""
    helpers.replays_with_the_old_rule(addon, lambda: _half_painted("Old"), OLD_CURVE, 8)


@pytest.mark.parametrize("method, independent", [('CUBIC', True), ('GAUSS', False)])
def test_the_old_curve_switched_where_it_changes_nothing_leaves_the_run_as_it_was(addon, method, independent):
    # The cubic method takes the weights as they are, and without Resolution Independent both curves are
    # the same: a switch mid-run must not give the solver the weights again (which restarts its momentum).
    obj = _half_painted("Run", independent=independent)  # one object: two built alike may differ in their last bits
    obj.gauss_stylization.method = method
    results = []
    for switch in (False, True):
        obj.gauss_stylization.old_paint_curve = False
        run = _session(addon, obj)
        try:
            run.step(3)
            if switch:
                obj.gauss_stylization.old_paint_curve = True
                assert run.sync_settings() is None
            run.step(3)
            results.append(helpers.coords(obj))
        finally:
            run.cancel()
    np.testing.assert_array_equal(results[0], results[1])
