"""The settings schema: properties, JSON, live changes and panel rows all follow it,
and what the solver owns comes from the solver."""

import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import helpers
from blender_process import blender_command


def _rna(addon, name):
    """The registered property ``name`` of the object settings or of a style slot."""
    for group in (addon.settings.properties.GaussSettings, addon.settings.properties.GaussStyleSlot):
        if name in group.bl_rna.properties:
            return group.bl_rna.properties[name]
    raise KeyError(name)


def test_solver_owned_settings_take_the_solvers_defaults_and_limits(addon):
    gauss_core = addon.native.core()
    assert set(gauss_core.LIMITS) <= set(gauss_core.DEFAULTS)
    for name, (low, high) in gauss_core.LIMITS.items():
        prop = _rna(addon, name)
        assert prop.default == pytest.approx(gauss_core.DEFAULTS[name], rel=1e-6), name
        # Blender keeps ranges in float32: equal up to that, and never wider, so a
        # value the property clamps is one the solver accepts.
        assert prop.hard_min == pytest.approx(low, rel=1e-6) and prop.hard_min >= low, name
        assert prop.hard_max == pytest.approx(high, rel=1e-6) and prop.hard_max <= high, name
    assert _rna(addon, "preset").default == gauss_core.DEFAULTS["preset"].upper()
    assert _rna(addon, "method").default == gauss_core.DEFAULTS["method"].upper()
    assert [(item.identifier, item.value) for item in _rna(addon, "method").enum_items] == \
        [(name.upper(), number) for number, name in enumerate(gauss_core.METHODS)]


def test_the_json_facts_of_the_build_are_the_modules(addon):
    gauss_core = addon.native.core()
    from_file = addon.native.read_facts_file(addon.native.FACTS_FILE)
    assert from_file.defaults == gauss_core.DEFAULTS
    assert from_file.limits == dict(gauss_core.LIMITS)
    assert from_file.presets == tuple(gauss_core.PRESETS)
    assert from_file.methods == tuple(gauss_core.METHODS)
    assert from_file.sizes == dict(gauss_core.SIZE_LIMITS)
    assert addon.native.facts() == from_file


def _configured(name):
    """An object whose every setting differs from its default."""
    obj = helpers.uv_sphere(16, 8)
    obj.name = name
    helpers.add_group(obj, "Pins", [0, 1])
    helpers.add_group(obj, "Top", range(10, 40))
    helpers.activate(obj)
    addon_settings = dict(lam=6.5, admm_iterations=3, iterations=12, output='SHAPE_KEY', pin_group="Pins",
                          show_gauss_sphere=True,
                          uncovered='UNSTYLED', active_style_index=1, styles=[
                              dict(name="Base", preset='SQUARE_PYRAMID', sigma=7.0, mu=2.0,
                                   orientation=(0.1, 0.2, 0.3), axis_contribution=0.25),
                              dict(name="Mine", preset='CUSTOM', vertex_group="Top",
                                   custom_normals=[(0, 0, 1), (1, 0, 0), (0, 1, 1)], active_normal_index=2)])
    helpers.settings_io.apply_dict(obj.gauss_stylization, addon_settings)
    return obj


def test_json_round_trip_keeps_every_setting(addon):
    source = _configured("Source")
    target = helpers.uv_sphere(16, 8)
    text = addon.settings_io.to_json(source.gauss_stylization)
    addon.settings_io.apply_json(target.gauss_stylization, text)
    assert addon.settings_io.to_dict(target.gauss_stylization) == addon.settings_io.to_dict(source.gauss_stylization)
    assert target.gauss_stylization.styles[1].active_normal_index == 2
    assert target.gauss_stylization.active_style_index == 1


def test_settings_writer_refuses_unknown_names_and_json_needs_every_setting(addon):
    settings = helpers.uv_sphere(8, 4).gauss_stylization
    with pytest.raises(KeyError, match="sigmaa"):
        addon.settings_io.add_slot(settings, dict(preset='CUBE', sigmaa=3.0))
    with pytest.raises(KeyError, match="lamda"):
        addon.settings_io.apply_dict(settings, dict(lamda=3.0))
    with pytest.raises(KeyError, match="missing"):
        addon.settings_io.apply_json(settings, '{"lam": 5.0}')


# For every setting that a live run must pass on: the spec of the slot and the object
# settings it starts with, and the value the artist changes it to mid-run.
LIVE_CHANGES = {
    ("slot", "preset"): ({}, {}, 'OCTAHEDRON'),
    ("slot", "sigma"): ({}, {}, 9.0),
    ("slot", "mu"): ({}, {}, 3.0),
    ("slot", "orientation"): ({}, {}, (0.3, 0.2, 0.1)),
    ("slot", "axis_contribution"): (dict(preset='CYLINDER'), {}, 0.9),
    ("slot", "vertex_group"): ({}, dict(uncovered='UNSTYLED'), "Top"),
    ("slot", "custom_normals"): (dict(preset='CUSTOM', custom_normals=[(0, 0, 1)]), {}, [(1, 0, 0)]),
    ("slot", "gauss_map"): (dict(preset='GAUSS_MAP', gauss_map=[(0, 0, 1, 0.5), (1, 0, 0, 0.5)]), {},
                            [(0, 1, 0, 1.0)]),
    ("object", "uncovered"): (dict(vertex_group="Top"), {}, 'FIRST_SLOT'),
    # A Region of weight 0.5 (LIVE_MESHES), where the two curves differ (at 0 and 1 they agree).
    ("object", "old_paint_curve"): (dict(vertex_group="Half"), dict(uncovered='UNSTYLED'), True),
    ("object", "pin_group"): ({}, {}, "Pins"),
    ("object", "lam"): ({}, {}, 8.0),
    ("object", "method"): ({}, {}, 'CUBIC'),
    ("object", "cubic_lambda"): ({}, dict(method='CUBIC'), 0.8),
    ("object", "admm_iterations"): ({}, {}, 3),
    ("object", "keep_volume"): ({}, {}, True),
    # Suzanne's eyes touch her head: at lambda 20 the guard holds them back.
    ("object", "avoid_self_intersections"): ({}, dict(lam=20.0), True),
    ("object", "resolution_independent"): ({}, {}, False),  # on for a new object
    ("object", "weigh_finer_faces"): ({}, {}, True),  # Suzanne's faces are finer than the reference
    ("object", "square_flat_regions"): ({}, {}, True),  # on the mesh of LIVE_MESHES
    ("object", "paper_step_any_sigma"): (dict(sigma=12.0), {}, True),  # acts above PAPER_STEP_MAX_SIGMA
}
# The mesh a live change is tried on where Suzanne would not show it (default: helpers.suzanne(levels=1)).
def _half_painted_suzanne():
    obj = helpers.suzanne(levels=1)
    helpers.add_group(obj, "Half", range(len(obj.data.vertices)), weight=0.5)
    return obj


LIVE_MESHES = {
    ("object", "square_flat_regions"): helpers.capped_cylinder,  # Suzanne has no large flat region
    ("object", "old_paint_curve"): _half_painted_suzanne,
}
# Live settings that change what the solver says about the shape, not the shape: the value changed to.
LIVE_READOUTS = {
    ("object", "tolerance"): 0.25,  # what `converged` compares with
}


def _live_fields(addon):
    Live = addon.settings.fields.Live
    return ({("object", f.name) for f in addon.settings.schema.OBJECT if f.live is not Live.NOTHING
             and not isinstance(f, addon.settings.fields.Slots)}
            | {("slot", f.name) for f in addon.settings.schema.SLOT if f.live is not Live.NOTHING})


def test_every_live_setting_has_a_case_below(addon):
    assert set(LIVE_CHANGES) | set(LIVE_READOUTS) == _live_fields(addon)


@pytest.mark.parametrize("owner, name", sorted(LIVE_READOUTS), ids=["-".join(k) for k in sorted(LIVE_READOUTS)])
def test_a_readout_setting_changed_mid_run_reaches_the_solver(addon, owner, name):
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE')
    settings = obj.gauss_stylization
    run = addon.run.session.Session(obj)
    run.step(2)
    field = addon.settings.schema.field(addon.settings.schema.OBJECT, name)
    field.write(settings, LIVE_READOUTS[owner, name])
    assert run.sync_settings() is None
    assert getattr(run.solver, name) == field.read(settings)
    run.cancel()


@pytest.mark.parametrize("owner, name", sorted(LIVE_CHANGES), ids=["-".join(k) for k in sorted(LIVE_CHANGES)])
def test_a_setting_changed_mid_run_reaches_the_solver(addon, owner, name):
    slot_spec, object_settings, changed = LIVE_CHANGES[owner, name]
    obj = LIVE_MESHES[owner, name]() if (owner, name) in LIVE_MESHES else helpers.suzanne(levels=1)
    start = helpers.coords(obj)
    helpers.add_group(obj, "Top", np.flatnonzero(start[:, 2] > 0))
    helpers.add_group(obj, "Pins", np.flatnonzero(start[:, 2] > 0.3))
    addon.settings_io.apply_dict(obj.gauss_stylization, dict(object_settings, styles=[slot_spec]))
    settings = obj.gauss_stylization
    target = settings if owner == "object" else settings.styles[0]
    schema = addon.settings.schema
    field = schema.field(schema.OBJECT if owner == "object" else schema.SLOT, name)
    original = field.read(target)
    results = []
    for change in (False, True):
        run = addon.run.session.Session(obj)
        run.step(2)
        if change:
            field.write(target, changed)
            assert run.sync_settings() is None
        run.step(3)
        results.append(run.result.copy())
        run.cancel()
        field.write(target, original)
    assert not np.array_equal(results[0], results[1]), "changing %s mid-run did not reach the solver" % name


class _Layout:
    """Records the rows a panel draws (a stand-in for bpy.types.UILayout)."""

    def __init__(self, rows):
        self.rows = rows

    def prop(self, owner, name, text=None):
        self.rows.append(name)

    def prop_search(self, owner, name, *_args, text=None):
        self.rows.append(name)

    def template_list(self, _list_type, _list_id, owner, name, *_args, rows=None):
        self.rows.append(name)

    def __getattr__(self, _name):  # label, operator, separator, row, column: no setting
        return lambda *args, **kwargs: self


def _slot_rows(addon, preset):
    obj = helpers.suzanne(levels=0)
    slot = helpers.add_slot(obj, preset)
    rows = []
    addon.view.sidebar.draw_rows(_Layout(rows), obj, slot, addon.settings.schema.SLOT, addon.settings.fields.Panel.SLOT)
    return rows


def test_panel_rows_follow_the_schema(addon):
    assert _slot_rows(addon, 'CYLINDER') == ["preset", "sigma", "mu", "orientation", "axis_contribution",
                                             "vertex_group"]
    assert _slot_rows(addon, 'CUSTOM') == ["preset", "sigma", "mu", "orientation", "vertex_group",
                                           "custom_normals"]


def test_axis_weight_is_shown_only_for_presets_the_solver_gives_rings(addon):
    # The axis weight acts only where there are rings; shown for other presets it would do nothing.
    gauss_core = addon.native.core()
    assert "axis_contribution" not in _slot_rows(addon, 'CUBE')
    for name in gauss_core.PRESETS:
        has_rings = len(gauss_core.Style.preset(name).ring_offsets) > 0
        assert ("axis_contribution" in _slot_rows(addon, name.upper())) == has_rings, name
    assert {name for name in gauss_core.PRESETS if len(gauss_core.Style.preset(name).ring_offsets)} == \
        {"cylinder", "cone", "double_cone"}


_WITHOUT_MODULE = """
import sys, bpy
sys.path.insert(0, sys.argv[-1])
sys.modules["gauss_core"] = None  # nor a top-level one (an extension's wheel, installed beside it)
import gauss_stylization
gauss_stylization.register()
slot = gauss_stylization.settings.properties.GaussStyleSlot.bl_rna.properties
print("PRESETS", [(item.identifier, item.value) for item in slot["preset"].enum_items])
print("SIGMA", slot["sigma"].default, slot["sigma"].hard_min, slot["sigma"].hard_max)
bpy.ops.mesh.primitive_cube_add()
try:
    bpy.ops.object.gauss_stylize(iterations=1)
except RuntimeError as exc:
    print("REFUSED", exc)
"""


def _run_without_module(tmp_path, keep_facts):
    package = tmp_path / "gauss_stylization"
    shutil.copytree(os.path.join(helpers.ADDON_DIR, "gauss_stylization"), package,
                    ignore=shutil.ignore_patterns("gauss_core*", "__pycache__"))
    if not keep_facts:
        os.remove(package / "core_facts.json")
    result = subprocess.run(blender_command(_WITHOUT_MODULE, [str(tmp_path)], factory_startup=True, exit_code=False),
                            capture_output=True, text=True, timeout=120)
    return result.stdout + result.stderr


def test_without_the_native_module_the_addon_registers_from_the_build_facts(addon, tmp_path):
    gauss_core = addon.native.core()
    out = _run_without_module(tmp_path, keep_facts=True)
    expected = [(name.upper(), number) for number, name in enumerate(gauss_core.PRESETS)] + [("CUSTOM", 99),
                                                                                             ("GAUSS_MAP", 98)]
    assert "PRESETS %s" % expected in out, out
    sigma = next(line.split()[1:] for line in out.splitlines() if line.startswith("SIGMA "))
    assert [float(x) for x in sigma] == pytest.approx([gauss_core.DEFAULTS["sigma"], *gauss_core.LIMITS["sigma"]],
                                                      rel=1e-6), out
    assert "REFUSED" in out and "gauss_core native module" in out, out


def test_without_module_and_facts_the_import_error_says_what_to_do(tmp_path):
    out = _run_without_module(tmp_path, keep_facts=False)
    assert "PRESETS" not in out and "core_facts.json is unreadable" in out and "Reinstall" in out, out
