"""What the sidebar panels show and how they say it: tooltips, names, precision, rows that fit
the sidebar, the custom-normal rows, notes before a click, and the live run's distance from
convergence. Panels are drawn into a recording stand-in for Blender's layout (headless)."""

import bpy
import numpy as np
import pytest

import helpers
from panel_recorder import Layout, draw, labels, props


def _all_panels(addon):
    return [addon.ui.VIEW3D_PT_gauss_stylization, addon.ui.VIEW3D_PT_gauss_styles, addon.ui.VIEW3D_PT_gauss_solver,
            addon.bake.bake_ui.VIEW3D_PT_gauss_bake]


def _operator_rna(idname):
    module, name = idname.split(".")
    return getattr(getattr(bpy.ops, module), name).get_rna_type()


def test_every_operator_tooltip_is_one_paragraph_without_the_docstrings_indent(addon):
    operators = [cls for cls in addon.classes if issubclass(cls, bpy.types.Operator)]
    assert len(operators) > 10
    for cls in operators:
        text = _operator_rna(cls.bl_idname).description
        assert text and "\n" not in text and "  " not in text and text == text.strip(), (cls.__name__, text)


def test_every_number_shows_its_default_and_smallest_slider_value(addon):
    schema = addon.settings.schema
    for table, group in ((schema.OBJECT, addon.settings.properties.GaussSettings),
                         (schema.SLOT, addon.settings.properties.GaussStyleSlot)):
        for field in table:
            if isinstance(field, addon.settings.fields.Float):
                decimals = group.bl_rna.properties[field.name].precision
                for value in (field.default, field.soft[0]):
                    assert value == 0 or round(value, decimals) != 0, (field.name, value, decimals)
    tolerance = addon.settings.properties.GaussSettings.bl_rna.properties["tolerance"]
    assert "%.*f" % (tolerance.precision, schema.FACTS.defaults["tolerance"]) != "0.00"


def test_the_redo_panel_calls_the_steps_what_the_solver_panel_calls_them(addon):
    field = addon.settings.schema.field(addon.settings.schema.OBJECT, "iterations")
    redo = _operator_rna("object.gauss_stylize").properties["iterations"].name
    assert redo == field.label == "Script Steps"
    assert "iterations" in props(draw(addon.ui.VIEW3D_PT_gauss_solver, _context_with_object()))


def _context_with_object(obj=None):
    obj = obj or helpers.activate(helpers.suzanne(levels=0))
    return bpy.context


def test_every_label_fits_the_sidebar_or_wraps(addon):
    objects = [helpers.suzanne(levels=0) for _ in range(3)]
    for obj in objects:
        obj.name = "spot_triangulated_2930_with_a_long_name"
        obj.select_set(True)
    obj = helpers.activate(objects[0])
    settings = obj.gauss_stylization
    settings.method = 'CUBIC'
    sidebar = addon.view.sidebar
    width = sidebar.label_width()
    for panel in _all_panels(addon):
        for text in labels(draw(panel)):
            assert sidebar.text_width(text) <= width, (panel.__name__, text, sidebar.text_width(text), width)


def test_wrapping_breaks_between_words_and_keeps_every_word(addon):
    wrap = addon.view.sidebar.wrap_text
    text = "Esc: cancel (nothing is written) and more words here"
    lines = wrap(text, 12, len)
    assert " ".join(lines) == text and all(len(line) <= 12 or " " not in line for line in lines)
    assert wrap("", 10, len) == []
    assert wrap("Writes /tmp/folder/a_long_file_name.pc2", 12, len) == [
        "Writes", "/tmp/folder/", "a_long_file_", "name.pc2"]
    assert wrap("a b c", 3, len) == ["a b", "c"]
    # An object name too long for a line is cut after an underscore, not inside a number.
    assert wrap("spot_triangulated_2930: step 5", 20, len) == ["spot_triangulated_", "2930: step 5"]


def test_a_custom_normal_is_one_row_with_its_number_and_x_y_z(addon):
    obj = helpers.activate(helpers.suzanne(levels=0))
    slot = helpers.add_slot(obj, 'CUSTOM', custom_normals=[(0, 0, 1), (-0.79, -0.19, 0.58)])
    layout = Layout()
    addon.ui.GAUSS_UL_normals.draw_item(None, bpy.context, layout, slot, slot.custom_normals[1], 'NONE',
                                        slot, "active_normal_index", 1)
    # One label, spaces between the numbers: in a label each, "-0.79-0.19 0.58" ran together.
    assert layout.rows == [("label", "2", 'NONE'), ("label", "-0.79 -0.19 0.58", 'NONE')]
    slot.active_normal_index = 1  # ... and is edited under the list
    assert ("prop", "vector", "#2", -1) in draw(addon.ui.VIEW3D_PT_gauss_styles)


def test_a_slot_name_gets_its_row_and_the_region_only_where_both_fit(addon):
    """Issue 26: in half of the list's row, names were cut to "Stre...". At the default sidebar width a
    long name takes the row (the Region as its icon); a short one leaves room for the Region's name."""
    obj = helpers.activate(helpers.suzanne(levels=0))
    helpers.add_group(obj, "Head", range(10))
    long_name = helpers.add_slot(obj, 'CUBE', name="Stretched Cube")
    short = helpers.add_slot(obj, 'CUBE', group="Head")
    rows = {}
    for slot in (long_name, short):
        layout = Layout()
        addon.ui.GAUSS_UL_styles.draw_item(None, bpy.context, layout, obj.gauss_stylization, slot, 'NONE',
                                           obj.gauss_stylization, "active_style_index", 0)
        rows[slot.name] = layout.rows
    assert rows["Stretched Cube"] == [("prop", "name", "", -1)]
    assert rows["Cube"] == [("prop", "name", "", -1), ("label", "Head", 'NONE')]


def test_the_gauss_sphere_checkbox_shows_before_any_slot_and_stylize_says_what_it_adds(addon):
    obj = helpers.activate(helpers.suzanne(levels=0))
    rows = draw(addon.ui.VIEW3D_PT_gauss_styles)
    assert len(obj.gauss_stylization.styles) == 0 and "show_gauss_sphere" in props(rows)
    assert "Stylize adds a Cube style" in " ".join(labels(rows))  # (wrapped to the sidebar's width)


def test_the_panel_says_before_the_click_that_the_modifiers_keep_the_result_out_of_the_mesh(addon):
    obj = helpers.activate(helpers.suzanne(levels=0))
    obj.modifiers.new("Subdivision", 'SUBSURF')
    obj.gauss_stylization.use_modifiers = True
    bpy.context.view_layer.update()
    said = " ".join(labels(draw(addon.ui.VIEW3D_PT_gauss_stylization)))
    assert "The modifiers change the vertices or faces" in said and "New Object" in said
    obj.gauss_stylization.output = 'NEW_OBJECT'
    assert "The modifiers change" not in " ".join(labels(draw(addon.ui.VIEW3D_PT_gauss_stylization)))
    obj.gauss_stylization.output = 'MESH'
    obj.modifiers["Subdivision"].levels = 0  # vertices as in the mesh: nothing to say
    bpy.context.view_layer.update()
    assert "The modifiers change" not in " ".join(labels(draw(addon.ui.VIEW3D_PT_gauss_stylization)))


def test_a_kept_new_object_hides_the_original(addon):
    obj = helpers.activate(helpers.suzanne(levels=0))
    assert helpers.stylize(2, output='NEW_OBJECT') == {'FINISHED'}
    new = bpy.data.objects[obj.name + addon.settings.schema.NEW_OBJECT_SUFFIX]
    assert obj.hide_get() and not new.hide_get() and bpy.context.view_layer.objects.active == new


def _settling(lines):
    return [line for line in lines if line[0].startswith("settling")]


def test_a_live_run_says_in_words_how_far_it_has_settled_and_the_numbers_in_the_tooltip(addon):
    """Issue 26: "change 2.4e-2 \u2192 1.0e-3" read as noise; now "settling, 80%", then "Converged"."""
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE')
    live = helpers.live_run([obj])
    session = live.sessions[0]
    try:
        assert not _settling(live.panel_lines())  # before the first step
        shown = []
        while not session.converged and session.steps < 300:
            live.tick(budget=0.0)  # one step
            if not session.converged:
                (text, icon, details), = _settling(live.panel_lines())
                shown.append(int(text[len("settling, "):-1]))
                assert text in live.status_text() and "\u2192" not in live.status_text()
                assert "e-" in details and "Tolerance" in details  # the numbers, in the tooltip
        assert session.converged and "Converged" in live.status_text() and not _settling(live.panel_lines())
        assert shown and max(shown) <= 99 and shown[-1] >= 50, shown  # never 100% before converged
        assert shown == sorted(shown), shown  # the last step's change rises at times; "settling" never goes back
    finally:
        live.cancel()


@pytest.mark.parametrize("change, tolerance, fraction", [
    (1.0, 1e-3, 0.0), (3.0, 1e-3, 0.0), (0.1, 1e-3, 1 / 3), (1e-2, 1e-4, 0.5), (1.001e-3, 1e-3, 0.99),
    (1e-9, 1e-3, 0.99), (float("inf"), 1e-3, None)])
def test_settling_is_the_change_on_a_log_scale_from_one_to_the_tolerance(addon, change, tolerance, fraction):
    found = addon.run.progress.settling_fraction(change, tolerance)
    assert found == fraction if fraction is None else found == pytest.approx(fraction)
    if fraction is not None:
        assert addon.run.progress.settling_text(found) == "settling, %d%%" % int(100 * found)


def test_the_pin_hint_shows_only_where_a_run_has_a_pin_group(addon):
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE')
    run = addon.operators.OBJECT_OT_gauss_stylize.key_hints
    live = helpers.live_run([obj])
    try:
        holder = type("Run", (), {"live": live})()
        assert addon.operators.PIN_HINT not in run(holder)
        helpers.add_group(obj, "Pins", range(10))
        obj.gauss_stylization.pin_group = "Pins"
        assert addon.operators.PIN_HINT in run(holder)
    finally:
        live.cancel()


def test_while_painting_the_hints_say_what_clicks_do(addon):
    # In Weight Paint a left-drag paints (modal_events lets clicks through): the hints must not offer
    # "Left-click: keep / Right-click: cancel" then, and must say how to go back, keep and cancel.
    obj = helpers.suzanne(levels=0)
    helpers.add_slot(obj, 'CUBE')
    hints = addon.operators.OBJECT_OT_gauss_stylize.key_hints
    live = helpers.live_run([obj])
    try:
        holder = type("Run", (), {"live": live})()
        assert any("Left-click" in hint for hint in hints(holder))
        bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
        painting = " | ".join(hints(holder))
        assert "Left-click" not in painting and "Right-click" not in painting
        assert "paint" in painting.lower() and "Object Mode" in painting
        assert "Enter: keep" in painting and "Esc: cancel" in painting
    finally:
        if obj.mode != 'OBJECT':
            bpy.ops.object.mode_set(mode='OBJECT')
        live.cancel()


def test_the_paint_region_button_paints_the_active_region_and_comes_back(addon):
    obj = helpers.suzanne(levels=0)
    helpers.add_group(obj, "Other", range(5))
    helpers.add_group(obj, "Paint", range(10))
    helpers.add_slot(obj, 'CUBE', "Paint")
    obj.vertex_groups.active_index = obj.vertex_groups["Other"].index
    assert bpy.ops.object.gauss_paint_region() == {'FINISHED'}
    assert obj.mode == 'WEIGHT_PAINT' and obj.vertex_groups.active.name == "Paint"
    assert bpy.ops.object.gauss_paint_region() == {'FINISHED'}
    assert obj.mode == 'OBJECT'


@pytest.mark.parametrize("euler, words", [
    ((0, 0, 0), "not turned"),
    ((90, 0, 0), "90.0 degrees about +X: the style's axes X along +X, Y along +Z, Z along -Y"),
    ((0, 0, -90), "90.0 degrees about -Z: the style's axes X along -Y, Y along +X, Z along +Z"),
    ((0, 30, 0), "30.0 degrees about +Y: the style's axes X along (0.87, 0.00, -0.50), Y along +Y, "
                 "Z along (0.50, 0.00, 0.87)"),
])
def test_auto_orient_says_the_rotation_in_words(addon, euler, words):
    from mathutils import Euler
    matrix = np.array(Euler(np.radians(euler), 'XYZ').to_matrix())
    assert addon.sphere.orientation.rotation_in_words(matrix).startswith(words)


def test_the_sphere_labels_the_object_axes_at_its_rim(addon):
    where = addon.sphere.gauss_sphere.Frame(100.0, 100.0, 50.0)
    reach = addon.sphere.gauss_sphere.AXIS_LABEL_REACH * 50.0
    # Seen from the front (-Y towards the viewer): X right, Z up, Y away from the viewer.
    front = np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], float)
    labels = {name: (x, y, facing) for name, x, y, facing in addon.sphere.gauss_sphere.axis_labels(front, where)}
    assert labels["X"] == pytest.approx((100 + reach, 100, True))
    assert labels["Z"] == pytest.approx((100, 100 + reach, True))
    assert labels["Y"][:2] == pytest.approx((100, 100)) and labels["Y"][2] is False
