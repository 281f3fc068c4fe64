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
    live = helpers.live_run([obj])
    solver = live.sessions[0].solver
    said = []  # (vertices the last step held back, whether the status line said so) after each tick
    for _ in range(20):
        live.tick()
        said.append((solver.held_vertices, "held back" in live.status_text()))
    held_text = live.status_text() if said[-1][0] else None
    live.cancel()
    assert any(held for held, _ in said), said  # Suzanne's eyes touch her head: the guard has work to do
    assert all(mentioned == (held > 0) for held, mentioned in said), (said, held_text)
