"""Avoid Self-Intersections in the add-on: the setting reaches the solver, and a stylized mesh that
crossed itself without it does not with it, counted as Blender's 3D-Print toolbox counts
(helpers.crossing_pairs: BVHTree.overlap of the triangulated mesh with itself)."""
import os

import pytest

import helpers


@pytest.fixture
def spot():
    if not os.path.exists(os.path.join(helpers.MESHES, "small", "spot_triangulated_2930.obj")):
        pytest.skip("../shared/meshes not present")
    return helpers.import_obj("small/spot_triangulated_2930.obj")


def test_spot_under_a_strong_cube_style_stays_clean_with_the_setting(addon, spot):
    assert helpers.crossing_pairs(spot) == 0
    original = helpers.coords(spot)
    counts = {}
    helpers.add_slot(spot, 'CUBE')
    for avoid in (False, True):
        assert helpers.stylize(0, lam=20.0, avoid_self_intersections=avoid) == {'FINISHED'}
        counts[avoid] = helpers.crossing_pairs(spot)
        helpers.mesh_io.write_vertex_coords(spot.data, original)  # the next run starts from the input
    assert counts[False] > 0 and counts[True] == 0, counts


def test_the_setting_is_off_by_default_and_the_solvers_default(addon):
    obj = helpers.suzanne(levels=0)
    assert obj.gauss_stylization.avoid_self_intersections is False
    assert addon.native.facts().defaults["avoid_self_intersections"] is False


def test_a_live_run_says_when_it_holds_vertices_back(addon):
    obj = helpers.suzanne(levels=1)
    helpers.add_slot(obj, 'CUBE')
    obj.gauss_stylization.lam = 20.0
    obj.gauss_stylization.avoid_self_intersections = True
    run = addon.run.session.Session(obj)
    held = 0
    for _ in range(20):
        run.step(1)
        held = max(held, run.solver.held_vertices)
    run.cancel()
    assert held > 0  # Suzanne's eyes touch her head: the guard has work to do
