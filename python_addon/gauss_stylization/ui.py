"""Sidebar panels (3D view > Sidebar > Gauss) and the style-slot lists."""

import blf
import bpy

from . import native, operators, output, runs, schema, styles
from .errors import NativeModuleError
from .fields import Panel
from .targets import stylize_objects

CATEGORY = "Gauss"


class GAUSS_UL_styles(bpy.types.UIList):
    """Style slots; later slots win where their regions overlap."""

    def draw_item(self, context, layout, data, slot, icon, active_data, active_propname, index):
        split = layout.split(factor=0.5)
        split.prop(slot, "name", text="", emboss=False)
        # The slot's region: its vertex group, or the whole mesh when none is set.
        if slot.vertex_group:
            split.label(text=slot.vertex_group, icon='GROUP_VERTEX')
        else:
            split.label(text="All", icon='MESH_DATA')


class GAUSS_UL_normals(bpy.types.UIList):
    """Custom normals, one row each: its number, then X Y Z to two decimals (number fields would be
    too narrow to read in the sidebar). The active one is edited under the list and highlighted on
    the Gauss sphere."""

    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        split = layout.split(factor=0.16)
        split.label(text="%d" % (index + 1))
        row = split.row(align=True)
        for value in item.vector:
            row.label(text="%.2f" % value)


def _mesh_object(context):
    obj = context.active_object
    return obj if obj is not None and obj.type == 'MESH' else None


class _GaussPanel:
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = CATEGORY


class _GaussSubPanel(_GaussPanel):
    """A sub-panel of the Gauss Stylization panel, shown when a mesh object is active."""
    bl_parent_id = "VIEW3D_PT_gauss_stylization"

    @classmethod
    def poll(cls, context):
        return _mesh_object(context) is not None


class VIEW3D_PT_gauss_stylization(_GaussPanel, bpy.types.Panel):
    bl_label = "Gauss Stylization"

    def draw(self, context):
        layout = self.layout
        try:
            native.core()
        except NativeModuleError as exc:
            wrapped_label(layout, str(exc), 'ERROR')
        for run in runs.live_runs():
            _draw_run_state(layout, run)
        obj = _mesh_object(context)
        if obj is None:
            layout.label(text="Select a mesh object", icon='INFO')
            return
        count = len(stylize_objects(context))
        if count > 1 and not runs.live_runs():
            wrapped_label(layout, "Stylize acts on the %d selected meshes" % count, 'INFO')
        row = layout.row(align=True)
        row.scale_y = 1.5
        row.operator("object.gauss_stylize", icon='PLAY')
        row.operator("object.gauss_stylize_reset", icon='LOOP_BACK')
        _draw_rows(_split_column(layout), obj, obj.gauss_stylization, schema.OBJECT, Panel.MAIN)
        note = output.refusal_before_run(obj, context.view_layer.depsgraph)
        if note:
            wrapped_label(layout, note, 'ERROR')


class VIEW3D_PT_gauss_styles(_GaussSubPanel, bpy.types.Panel):
    bl_label = "Styles"

    def draw(self, context):
        obj = _mesh_object(context)
        settings = obj.gauss_stylization
        layout = self.layout
        _draw_rows(_split_column(layout), obj, settings, schema.OBJECT, Panel.METHOD)
        if schema.is_cubic(settings):
            wrapped_label(layout, "Cubic uses each slot's Mu and Rotation, not its Style or Sigma", 'INFO')
        row = layout.row()
        row.template_list("GAUSS_UL_styles", "", settings, "styles", settings, "active_style_index", rows=3)
        buttons = row.column(align=True)
        buttons.operator("object.gauss_style_add", icon='ADD', text="")
        buttons.operator("object.gauss_style_remove", icon='REMOVE', text="")
        buttons.separator()
        buttons.operator("object.gauss_style_move", icon='TRIA_UP', text="").direction = 'UP'
        buttons.operator("object.gauss_style_move", icon='TRIA_DOWN', text="").direction = 'DOWN'
        tools = layout.column(align=True)
        tools.operator("object.gauss_style_from_object", icon='OBJECT_DATA')
        tools.operator("object.gauss_style_auto_orient", icon='ORIENTATION_GIMBAL')
        _draw_rows(_split_column(layout), obj, settings, schema.OBJECT, Panel.SPHERE)
        if not settings.styles:
            wrapped_label(layout, "Stylize adds a %s style" % schema.DEFAULT_PRESET_LABEL, 'INFO')
            return
        col = _split_column(layout)
        _draw_rows(col, obj, settings, schema.OBJECT, Panel.STYLES)
        slot = styles.active_slot(settings)
        if slot is not None:
            col.separator()
            _draw_rows(col, obj, slot, schema.SLOT, Panel.SLOT)


def _draw_run_state(layout, run):
    """What a live run (a Stylize, or a bake: bake_operators.py) does: its objects and how far
    they are, and the keys that end it."""
    title, lines, hints = run.panel_state()
    box = layout.box().column(align=True)
    box.label(text=title, icon='TIME')
    for text, icon in lines:
        wrapped_label(box, text, icon)
    for hint in hints:
        wrapped_label(box, hint)


def _split_column(layout):
    col = layout.column()
    col.use_property_split = True
    col.use_property_decorate = False
    return col


def _draw_rows(layout, obj, owner, table, panel):
    """The rows of ``panel``: every field of ``table`` placed there that is shown for ``owner``."""
    for field in schema.rows(table, panel):
        if field.shown(owner):
            _WIDGETS[field.widget](layout, obj, owner, field)


def _draw_prop(layout, _obj, owner, field):
    layout.prop(owner, field.name, text=field.text or field.label)


def _draw_vertex_group(layout, obj, owner, field):
    layout.prop_search(owner, field.name, obj, "vertex_groups", text=field.text or field.label)


def _draw_custom_normals(layout, _obj, slot, field):
    layout.label(text=field.label)
    row = layout.row()
    row.template_list("GAUSS_UL_normals", "", slot, "custom_normals", slot, "active_normal_index", rows=5)
    buttons = row.column(align=True)
    buttons.operator("object.gauss_normal_add", icon='ADD', text="")
    buttons.operator("object.gauss_normal_remove", icon='REMOVE', text="")
    index = slot.active_normal_index
    if 0 <= index < len(slot.custom_normals):
        layout.prop(slot.custom_normals[index], "vector", text="#%d" % (index + 1))  # short: Blender adds " X"
    layout.operator("object.gauss_normals_from_faces", icon='FACESEL')
    if not slot.custom_normals:
        wrapped_label(layout, "Add at least one normal", 'ERROR')


class VIEW3D_PT_gauss_solver(_GaussSubPanel, bpy.types.Panel):
    bl_label = "Solver"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        obj = _mesh_object(context)
        _draw_rows(_split_column(self.layout), obj, obj.gauss_stylization, schema.OBJECT, Panel.SOLVER)


_WIDGETS = {"prop": _draw_prop, "vertex_group": _draw_vertex_group, "normals": _draw_custom_normals}


# What a label row loses to the panel's margins, a box, its icon and the sidebar's tab strip, in
# Blender's UI units (20 px at scale 1), and the font size of labels; measured on Blender 3.4's sidebar.
LABEL_MARGIN_UNITS = 5.0
DEFAULT_SIDEBAR_PX = 220.0  # Blender's default sidebar width at scale 1 (UI_SIDEBAR_PANEL_WIDTH)
LABEL_POINTS = 11.0


def ui_scale(context):
    """The UI's scale factor. Without a window (blender -b, Blender as a Python module) Blender leaves
    it at 0 (no display to take a DPI from), so the artist's Resolution Scale stands in for it: at 0,
    Blender 4.x and later measure text as if every character were a pixel wide and no label fit."""
    return context.preferences.system.ui_scale or context.preferences.view.ui_scale


def label_width(context=None):
    """Pixels a label's text has in a sidebar panel row: the sidebar's width (Blender's default
    where there is none, as in background mode) less margins, icon and tab strip."""
    context = context or bpy.context
    region = context.region
    scale = ui_scale(context)
    width = region.width if region is not None and region.type == 'UI' else DEFAULT_SIDEBAR_PX * scale
    return max(width - LABEL_MARGIN_UNITS * 20.0 * scale, 2 * 20.0 * scale)  # never so narrow nothing fits


def text_width(text, context=None):
    """Pixels ``text`` takes in the UI's font at the current UI scale."""
    context = context or bpy.context
    blf.size(0, LABEL_POINTS * ui_scale(context))  # no DPI argument: gone in 4.0
    return blf.dimensions(0, text)[0]


def _pieces(word, width, measure):
    """A word wider than ``width`` (a file path, an object name) in pieces that fit, cut after a
    '/', '\\' or '_' where one is near, else wherever it must be."""
    pieces = []
    while measure(word) > width and len(word) > 1:
        cut = len(word) - 1
        while cut > 1 and measure(word[:cut]) > width:
            cut -= 1
        separator = max(word.rfind(mark, 0, cut) for mark in "/\\_")
        cut = separator + 1 if separator >= cut // 2 else cut
        pieces.append(word[:cut])
        word = word[cut:]
    return pieces + [word]


def wrap_text(text, width, measure):
    """``text`` in lines no wider than ``width`` (by ``measure``), broken between words; a word
    wider than a line (a file path) is cut into pieces that fit."""
    lines, line = [], ""
    for word in text.split():
        first, *rest = _pieces(word, width, measure)
        candidate = (line + " " + first).strip()
        if line and measure(candidate) > width:
            lines.append(line)
            candidate = first
        line = candidate
        for piece in rest:  # the pieces of a cut word each fill a line
            lines.append(line)
            line = piece
    return lines + [line] if line else lines


def wrapped_label(layout, text, icon='NONE'):
    """A label that wraps to the sidebar's width instead of being cut off; the icon on its first line."""
    col = layout.column(align=True)
    lines = wrap_text(text, label_width(), text_width)
    for number, part in enumerate(lines):
        col.label(text=part, icon=icon if number == 0 else ('BLANK1' if icon != 'NONE' else 'NONE'))


classes = (GAUSS_UL_styles, GAUSS_UL_normals,
           VIEW3D_PT_gauss_stylization, VIEW3D_PT_gauss_styles, VIEW3D_PT_gauss_solver)
