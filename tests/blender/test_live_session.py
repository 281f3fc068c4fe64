"""The live run behind the modal operator, driven step by step without a window.

The windowed test (run_windowed.sh) drives the real modal operator; these
tests pin down what each tick does with settings changed in the panel.
"""

import math

import bpy
import numpy as np
import pytest

import helpers


def _session(addon, obj):
    addon.run.session.ensure_style_slot(obj.gauss_stylization)
    return addon.run.session.Session(obj)


def test_style_changes_apply_without_refactoring(addon):
    obj = helpers.suzanne(levels=1)
    run = _session(addon, obj)
    run.step()
    factorizations = run.solver.factorization_count
    slot = obj.gauss_stylization.styles[0]
    slot.sigma, slot.mu, slot.orientation = 9.0, 2.0, (0.3, 0.0, 0.0)
    slot.preset = 'OCTAHEDRON'
    assert run.sync_settings() is None
    run.step()
    assert run.solver.factorization_count == factorizations
    obj.gauss_stylization.lam = 7.0
    obj.gauss_stylization.admm_iterations = 2
    assert run.sync_settings() is None
    assert (run.solver.lam, run.solver.admm_iterations) == (7.0, 2)
    run.cancel()


def test_pin_group_change_applies_at_next_step(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    pinned = np.flatnonzero(start[:, 2] > 0.3)
    helpers.add_group(obj, "Pins", pinned)
    run = _session(addon, obj)
    run.step(5)
    assert np.abs(helpers.coords(obj)[pinned] - start[pinned]).max() > 1e-3
    factorizations = run.solver.factorization_count
    obj.gauss_stylization.pin_group = "Pins"
    assert run.sync_settings() is None
    assert run.solver.factorization_count > factorizations
    run.cancel()


def test_invalid_change_pauses_instead_of_failing(addon):
    obj = helpers.suzanne(levels=1)
    run = _session(addon, obj)
    obj.gauss_stylization.styles[0].preset = 'CUSTOM'
    assert "no normals" in run.sync_settings()
    obj.gauss_stylization.styles[0].set_custom_normals([(0, 0, 1)])
    assert run.sync_settings() is None
    run.cancel()


def test_new_region_assignment_applies_at_next_step(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > 0))
    run = _session(addon, obj)
    obj.gauss_stylization.uncovered = 'UNSTYLED'
    slot = obj.gauss_stylization.styles[0]
    slot.vertex_group = "Top"
    assert run.sync_settings() is None
    helpers.add_slot(obj, 'CUSTOM', "Top").set_custom_normals([(0, 0, 1)])
    assert run.sync_settings() is None
    run.step(3)
    run.cancel()


def test_cancel_restores_mesh_bit_exactly(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    run = _session(addon, obj)
    run.step(10)
    assert not np.array_equal(helpers.coords(obj), start)
    run.cancel()
    assert np.array_equal(helpers.coords(obj), start)


def test_cancel_removes_the_shape_keys_it_created(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    obj.gauss_stylization.output = 'SHAPE_KEY'
    run = _session(addon, obj)
    run.step(10)
    assert obj.data.shape_keys is not None
    run.cancel()
    assert obj.data.shape_keys is None
    assert np.array_equal(helpers.coords(obj), start)


def test_cancel_restores_an_existing_stylized_key(addon):
    obj = helpers.suzanne(levels=1)
    obj.gauss_stylization.output = 'SHAPE_KEY'
    helpers.stylize(5)
    key = obj.data.shape_keys.key_blocks["Gauss Stylized"]
    key.value = 0.3
    before = helpers.key_coords(key)
    run = _session(addon, obj)
    run.step(10)
    run.cancel()
    key = obj.data.shape_keys.key_blocks["Gauss Stylized"]
    assert np.array_equal(helpers.key_coords(key), before) and key.value == np.float32(0.3)


def test_redo_repeats_a_live_run_with_the_settings_it_ended_with(addon):
    # The redo panel undoes to the state before the run (older settings) and
    # calls execute() with the settings the live run ended with.
    obj = helpers.suzanne(levels=1)
    slot = helpers.add_slot(obj, 'CUBE', sigma=9.0)
    ended_with = addon.settings_io.to_json(obj.gauss_stylization)
    slot.sigma, slot.preset = 4.0, 'OCTAHEDRON'
    assert bpy.ops.object.gauss_stylize(iterations=3, settings_json=ended_with) == {'FINISHED'}
    slot = obj.gauss_stylization.styles[0]
    assert (slot.sigma, slot.preset) == (9.0, 'CUBE')


def test_cancel_restores_base_key_and_vertices_of_a_keyed_mesh(addon):
    obj = helpers.suzanne(levels=1)
    basis = obj.shape_key_add(name="Basis", from_mix=False)
    obj.shape_key_add(name="Other", from_mix=False)
    start, basis_start = helpers.coords(obj), helpers.key_coords(basis)
    run = _session(addon, obj)
    run.step(10)
    assert not np.array_equal(helpers.evaluated_coords(obj), start)
    run.cancel()
    assert np.array_equal(helpers.coords(obj), start)
    assert np.array_equal(helpers.key_coords(obj.data.shape_keys.key_blocks["Basis"]), basis_start)


NAN_MID_RUN = [("settings", "lam", "Lambda"), ("slot", "sigma", "Sigma"), ("slot", "mu", "Mu"),
               ("slot", "axis_contribution", "Axis Contribution"), ("slot", "orientation", "Orientation"),
               ("normal", "vector", "custom normal 1")]


@pytest.mark.parametrize("owner, name, label", NAN_MID_RUN, ids=[case[1] for case in NAN_MID_RUN])
def test_nan_typed_in_mid_run_pauses_and_a_valid_value_resumes(addon, owner, name, label):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    slot = helpers.add_slot(obj, 'CUSTOM' if owner == "normal" else 'CUBE')
    if owner == "normal":
        slot.set_custom_normals([(0, 0, 1), (1, 0, 0)])
    target = {"settings": obj.gauss_stylization, "slot": slot,
              "normal": slot.custom_normals[0] if owner == "normal" else None}[owner]
    run = _session(addon, obj)
    run.step(3)
    applied = run.applied
    good = getattr(target, name)
    good = tuple(good) if target.bl_rna.properties[name].array_length else good
    size = target.bl_rna.properties[name].array_length
    setattr(target, name, (math.nan,) * size if size else math.nan)
    problem = run.sync_settings()
    assert problem is not None and label in problem
    assert run.applied == applied  # nothing reached the solver
    setattr(target, name, good)
    assert run.sync_settings() is None
    run.step()
    assert np.isfinite(helpers.coords(obj)).all()
    run.cancel()
    assert np.array_equal(helpers.coords(obj), start)


@pytest.mark.parametrize("which", ["Region", "Pin Group"])
def test_vertex_group_deleted_mid_run_pauses_with_a_message(addon, which):
    # The group's weights were read at start; once it is gone the run must not go on silently.
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > 0))
    slot = helpers.add_slot(obj, 'CUBE', "Top" if which == "Region" else "")
    if which == "Pin Group":
        obj.gauss_stylization.pin_group = "Top"
    run = _session(addon, obj)
    run.step(2)
    obj.vertex_groups.remove(obj.vertex_groups["Top"])
    problem = run.sync_settings()
    assert problem is not None and "'Top' was deleted while Stylize was running" in problem
    assert ("Style 'Cube'" if which == "Region" else "Pin Group") in problem
    assert run.sync_settings() == problem  # stays paused until a group that exists is picked
    if which == "Region":
        slot.vertex_group = ""
    else:
        obj.gauss_stylization.pin_group = ""
    assert run.sync_settings() is None
    run.step(2)
    run.cancel()
    assert np.array_equal(helpers.coords(obj), start)


def test_all_vertices_pinned_is_refused_and_pauses_mid_run(addon):
    obj = helpers.suzanne(levels=1)
    helpers.add_group(obj, "All", range(len(obj.data.vertices)))
    helpers.add_group(obj, "Some", range(10))
    helpers.add_slot(obj, 'CUBE')
    obj.gauss_stylization.pin_group = "All"
    with pytest.raises(addon.errors.SettingsError, match="nothing can move"):
        _session(addon, obj)
    obj.gauss_stylization.pin_group = "Some"
    run = _session(addon, obj)
    run.step()
    obj.gauss_stylization.pin_group = "All"
    assert "nothing can move" in run.sync_settings()
    run.cancel()


# The panel stays usable during a live run, so shape keys or the whole object
# can be deleted between two ticks. Writing into a deleted shape key crashed Blender.

def test_shape_keys_deleted_mid_run_with_shape_key_output(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    obj.gauss_stylization.output = 'SHAPE_KEY'
    run = _session(addon, obj)
    run.step(3)
    obj.shape_key_clear()
    with pytest.raises(addon.settings.validation.SettingsError, match="'Gauss Stylized' was deleted"):
        run.step()
    run.cancel()
    assert obj.data.shape_keys is None and np.array_equal(helpers.coords(obj), start)


def test_shape_keys_deleted_mid_run_with_mesh_output(addon):
    obj = helpers.suzanne(levels=1)
    obj.shape_key_add(name="Basis", from_mix=False)
    start = helpers.coords(obj)
    run = _session(addon, obj)
    run.step(3)
    obj.shape_key_clear()
    run.step(3)  # the mesh itself is still there to write to
    assert not np.array_equal(helpers.coords(obj), start)
    run.cancel()
    assert np.array_equal(helpers.coords(obj), start)


def test_basis_added_mid_run_is_restored_too(addon):
    obj = helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    run = _session(addon, obj)
    run.step(3)
    obj.shape_key_add(name="Basis", from_mix=False)  # made from the stylized shape
    run.step(3)
    run.cancel()
    assert np.array_equal(helpers.coords(obj), start)
    assert np.array_equal(helpers.key_coords(obj.data.shape_keys.key_blocks["Basis"]), start)


@pytest.mark.parametrize("output", ['MESH', 'SHAPE_KEY'])
def test_object_deleted_mid_run_its_mesh_is_still_restored(addon, output):
    # Another object may share the mesh, and undo reuses the mesh as it is in memory.
    obj = helpers.suzanne(levels=1)
    mesh, start = obj.data, helpers.coords(obj)
    obj.gauss_stylization.output = output
    objects = len(bpy.data.objects)
    run = _session(addon, obj)
    run.step(3)
    bpy.data.objects.remove(obj)
    assert not run.object_alive()
    run.cancel()
    out = np.empty_like(start)
    mesh.vertices.foreach_get("co", out.reshape(-1))
    assert np.array_equal(out, start) and mesh.shape_keys is None
    assert len(bpy.data.objects) == objects - 1  # the object borrowed to remove keys is gone


def test_mesh_freed_mid_run_cancel_touches_nothing(addon):
    obj = helpers.suzanne(levels=1)
    obj.gauss_stylization.output = 'SHAPE_KEY'
    run = _session(addon, obj)
    run.step(3)
    bpy.data.meshes.remove(obj.data)  # removes the object too
    assert not run.object_alive()
    run.cancel()  # no ReferenceError, no access to freed data


def test_a_long_live_run_keeps_only_the_last_step_and_tick_timings(addon):
    """An artist may leave a live run going for an hour (up to 100 ticks a second): its step and
    tick timings keep the last TIMINGS_KEPT, the newest last (what the status bar shows)."""
    obj = helpers.uv_sphere(8, 4)
    addon.run.session.ensure_style_slot(obj.gauss_stylization)
    schema = addon.settings.schema
    obj.gauss_stylization.tolerance = schema.field(schema.OBJECT, "tolerance").hard[0]  # status: ms, not "Converged"
    live = helpers.live_run([obj])
    session, kept = live.sessions[0], addon.run.session.TIMINGS_KEPT
    try:
        for tick in range(kept + 200):
            obj.gauss_stylization.lam = 4.0 + 0.01 * (tick % 2)  # a changed setting: never converged
            live.tick(budget=0.0)  # one step per tick
        assert session.steps == kept + 200
        assert len(session.step_ms) == kept and len(live.tick_ms) == kept
        session.step_ms.append(12.3)
        live.tick_ms.append(34.5)
        assert "12.3 ms/step, 34.5 ms/tick" in live.status_text()
        assert len(session.step_ms) == kept and len(live.tick_ms) == kept
    finally:
        live.cancel()
