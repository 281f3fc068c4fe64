import bpy


def test_operators_and_settings_exist(addon):
    assert bpy.ops.object.gauss_stylize.idname() == "OBJECT_OT_gauss_stylize"
    assert bpy.ops.object.gauss_stylize_reset.idname() == "OBJECT_OT_gauss_stylize_reset"
    assert "iterations" in bpy.ops.object.gauss_stylize.get_rna_type().properties
    assert hasattr(bpy.types.Object, "gauss_stylization")
    assert addon.bl_info["name"] == "Gauss Stylization" and addon.bl_info["category"] == "Mesh"
    panels = [name for name in dir(bpy.types) if name.startswith("VIEW3D_PT_gauss")]
    assert panels and all(getattr(bpy.types, p).bl_category == "Gauss" for p in panels)


def test_unregister_removes_everything_and_register_again(addon):
    addon.unregister()
    try:
        assert not hasattr(bpy.types.Object, "gauss_stylization")
        assert not hasattr(bpy.types, "OBJECT_OT_gauss_stylize")
        assert "gauss_stylize" not in dir(bpy.ops.object)
    finally:
        addon.register()
    assert hasattr(bpy.types.Object, "gauss_stylization")


def test_every_solver_preset_is_offered(addon):
    gauss_core = addon.native.core()
    items = addon.settings.properties.GaussStyleSlot.bl_rna.properties["preset"].enum_items.keys()
    assert set(items) == {name.upper() for name in gauss_core.PRESETS} | {"CUSTOM", "GAUSS_MAP"}


def test_default_settings(addon):
    import helpers
    settings = helpers.uv_sphere().gauss_stylization
    assert (settings.lam, settings.admm_iterations, settings.iterations) == (4.0, 1, 100)
    assert settings.output == 'MESH' and settings.uncovered == 'UNSTYLED'
    slot = settings.styles.add()
    assert (slot.preset, slot.sigma, slot.mu, slot.axis_contribution) == ('CUBE', 4.0, 1.0, 0.5)
    assert slot.bl_rna.properties["orientation"].subtype == 'EULER'
