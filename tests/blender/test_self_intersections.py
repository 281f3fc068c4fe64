"""Avoid Self-Intersections in the add-on: the setting reaches the solver, and a stylized mesh that
crossed itself without it does not with it, counted as Blender's 3D-Print toolbox counts
(helpers.crossing_pairs: BVHTree.overlap of the triangulated mesh with itself)."""
import os

import bmesh
import bpy
import numpy as np
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
        # The paper's strength (Resolution Independent off): Spot is finer than its reference density.
        assert helpers.stylize(0, lam=20.0, avoid_self_intersections=avoid,
                               resolution_independent=False) == {'FINISHED'}
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


def _two_spheres_with_a_cap(addon):
    """Two UV spheres 0.3 apart in one object, Pin Group 'Cap' on the first's side facing the second,
    and pin targets that push that cap 1.0 into the second (as a handle dragged there would)."""
    import bmesh
    import bpy
    from mathutils import Matrix, Vector
    bm = bmesh.new()
    for x in (0.0, 2.3):
        bmesh.ops.create_uvsphere(bm, u_segments=24, v_segments=12, radius=1.0,
                                  matrix=Matrix.Translation((x, 0.07, 0.03)))
    bmesh.ops.triangulate(bm, faces=bm.faces[:])  # the solver's triangles are the ones counted
    obj = helpers.object_from_bmesh(bm, "Spheres")
    cap = [v.index for v in obj.data.vertices if 0.8 < v.co.x < 1.2]  # the first sphere's side
    helpers.add_group(obj, "Cap", cap)
    obj.gauss_stylization.pin_group = "Cap"
    obj.gauss_stylization.lam = 0.0
    targets = [list(obj.data.vertices[i].co + Vector((1.0, 0, 0))) for i in cap]
    bpy.context.view_layer.objects.active = obj
    return obj, targets


def test_a_run_the_guard_stops_says_held_back_and_not_converged(addon):
    # The pinned cap pushed into the other sphere: without the guard it passes through and the run
    # converges; with it the run comes to rest short of it, and says the guard holds it, never
    # "Converged", which would tell the artist the style is done while the guard is what stopped it.
    obj, targets = _two_spheres_with_a_cap(addon)
    helpers.add_slot(obj, 'CUBE')
    original = helpers.coords(obj)
    for avoid in (False, True):
        obj.gauss_stylization.avoid_self_intersections = avoid
        live = helpers.live_run([obj])
        session = live.sessions[0]
        session.solver.set_pin_positions(targets)
        for _ in range(600):
            live.tick(budget=1e9)
            if live.converged:
                break
        assert live.converged == {session}, "never came to rest"
        text = live.status_text()
        if avoid:
            assert session.held_back and not session.converged
            assert "held back by Avoid Self-Intersections at %d vertices" % session.solver.held_vertices in text
            assert "Converged" not in text and "settling" not in text, text
            assert live.panel_title() == "Held back"
            assert any("held back" in line[0] and line[1] == 'ERROR' for line in live.panel_lines())
            assert helpers.crossing_pairs(obj) == 0
            # Where: Select Held Faces selects the faces around the vertices the guard held.
            assert not bpy.ops.object.gauss_select_held.poll()  # only for an object in a live run
            addon.run.runs.start([obj], live)
            try:
                assert bpy.ops.object.gauss_select_held() == {'FINISHED'}
            finally:
                addon.run.runs.forget(live)
            # Every vertex held in some step of the run, the last step's among them.
            held = set(session.held_anywhere.tolist())
            assert held >= set(session.solver.held_vertex_indices.tolist())
            around = {p.index for p in obj.data.polygons if held & set(p.vertices)}
            assert around and _selected_polygons(obj) == around
        else:
            assert session.converged and not session.held_back
            assert "Converged" in text and "held back" not in text, text
            assert helpers.crossing_pairs(obj) > 0
            addon.run.runs.start([obj], live)
            try:
                assert not bpy.ops.object.gauss_select_held.poll()  # nothing held
            finally:
                addon.run.runs.forget(live)
        steps = session.steps
        live.tick(budget=1e9)  # at rest: a tick does not step it
        assert session.steps == steps
        live.cancel()
        assert helpers.coords(obj).tolist() == original.tolist()


def _overlapping_polygons(obj):
    """Polygons of ``obj`` that cross another, by Blender's own BVHTree (as the 3D-Print toolbox)."""
    from mathutils.bvhtree import BVHTree
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    tree = BVHTree.FromBMesh(bm)
    found = {index for pair in tree.overlap(tree) for index in pair}
    bm.free()
    return found


def _the_same_as_blender_finds(obj, selected):
    """Does ``selected`` hold every polygon Blender's overlap finds, and besides those only polygons
    that cross a neighbour around a shared corner (a folded fan: Blender's overlap of a mesh with
    itself leaves out pairs that share a vertex; they cross all the same)?"""
    faces = _overlapping_polygons(obj)
    found = addon_crossings(obj)
    shared = all(set(obj.data.polygons[int(a)].vertices) & set(obj.data.polygons[int(b)].vertices)
                 for a, b in found.polygon_pairs if not {a, b} <= faces)
    return faces <= selected and shared and selected == set(found.polygons.tolist())


def addon_crossings(obj):
    import gauss_stylization
    return gauss_stylization.mesh.crossings.find(gauss_stylization.native.core(), obj,
                                                 bpy.context.evaluated_depsgraph_get())


def _selected_polygons(obj):
    chosen = np.zeros(len(obj.data.polygons), bool)
    obj.data.polygons.foreach_get("select", chosen)
    return set(np.flatnonzero(chosen).tolist())


def test_select_crossing_faces_selects_what_the_3d_print_toolbox_finds(addon, spot):
    """Spot stylized without the guard crosses itself: the operator selects those faces and says how
    many pairs, in Object Mode and in Edit Mode; with the guard, none."""
    helpers.add_slot(spot, 'CUBE')
    spot.gauss_stylization.resolution_independent = False  # the paper's strength, at which Spot crosses itself
    original = helpers.coords(spot)
    assert helpers.stylize(0, lam=20.0) == {'FINISHED'}
    assert helpers.crossing_pairs(spot) > 0
    assert bpy.ops.object.gauss_select_intersections() == {'FINISHED'}
    assert _the_same_as_blender_finds(spot, _selected_polygons(spot))
    found = addon_crossings(spot)
    reported = addon.crossing_operators.said(found)
    assert reported.startswith("%d pairs of faces cross" % len(found.pairs)), reported
    faces = _selected_polygons(spot)

    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    assert bpy.ops.object.gauss_select_intersections() == {'FINISHED'}
    edit = bmesh.from_edit_mesh(spot.data)
    assert {face.index for face in edit.faces if face.select} == faces
    bpy.ops.object.mode_set(mode='OBJECT')

    helpers.mesh_io.write_vertex_coords(spot.data, original)
    spot.data.update()
    assert helpers.stylize(0, lam=20.0, avoid_self_intersections=True) == {'FINISHED'}
    assert bpy.ops.object.gauss_select_intersections() == {'FINISHED'}
    assert _selected_polygons(spot) == set()


def test_select_crossing_faces_maps_triangles_back_to_polygons(addon):
    """Suzanne's quads: her eyes cross her head; the polygons selected are those Blender finds."""
    obj = helpers.activate(helpers.suzanne(levels=0))
    faces = _overlapping_polygons(obj)
    assert faces and any(len(obj.data.polygons[i].vertices) == 4 for i in faces)
    assert bpy.ops.object.gauss_select_intersections() == {'FINISHED'}
    assert _the_same_as_blender_finds(obj, _selected_polygons(obj))
    faces = _selected_polygons(obj)
    selected_vertices = np.zeros(len(obj.data.vertices), bool)
    obj.data.vertices.foreach_get("select", selected_vertices)
    assert set(np.flatnonzero(selected_vertices)) == {v for i in faces for v in obj.data.polygons[i].vertices}
