"""The sidebar's panel kit (3D view > Sidebar > Gauss): what every Gauss panel shares.

The panels' base classes (their tab, and the sub-panels' parent and poll), the rows of a settings
table (the fields of schema.py placed in a panel, each drawn by its widget), and labels that wrap to
the sidebar's width. The panels themselves are ui.py's and bake/bake_ui.py's.
"""

import blf
import bpy

from ..settings import schema

CATEGORY = "Gauss"


def mesh_object(context):
    obj = context.active_object
    return obj if obj is not None and obj.type == 'MESH' else None


class GaussPanel:
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = CATEGORY


class GaussSubPanel(GaussPanel):
    """A sub-panel of the Gauss Stylization panel, shown when a mesh object is active."""
    bl_parent_id = "VIEW3D_PT_gauss_stylization"

    @classmethod
    def poll(cls, context):
        return mesh_object(context) is not None


def split_column(layout):
    col = layout.column()
    col.use_property_split = True
    col.use_property_decorate = False
    return col


def draw_rows(layout, obj, owner, table, panel):
    """The rows of ``panel``: every field of ``table`` placed there that is shown for ``owner``."""
    for field in schema.rows(table, panel):
        if field.shown(owner):
            _WIDGETS[field.widget](layout, obj, owner, field)


def _draw_prop(layout, _obj, owner, field):
    layout.prop(owner, field.name, text=field.text or field.label)


def _draw_checkbox(layout, _obj, owner, field):
    # In a split column Blender puts a checkbox's label in the left column, where "Avoid
    # Self-Intersections" is cut off at the default sidebar width; across the row it fits.
    row = layout.row()
    row.use_property_split = False
    row.prop(owner, field.name, text=field.text or field.label)


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


def _draw_gauss_map(layout, _obj, slot, _field):
    count = len(slot.gauss_map)
    if count:
        layout.label(text="Example: %d directions" % count, icon='SPHERE')
    else:
        wrapped_label(layout, "No example yet: use From Gauss Map", 'ERROR')


_WIDGETS = {"prop": _draw_prop, "checkbox": _draw_checkbox, "vertex_group": _draw_vertex_group,
            "normals": _draw_custom_normals, "gauss_map": _draw_gauss_map}


# What a label row loses to the panel's margins, a box, its icon and the sidebar's tab strip, in
# Blender's UI units (20 px at scale 1), and the font size of labels; measured on Blender 3.4's sidebar.
LABEL_MARGIN_UNITS = 5.0
# What a list's row loses besides: the buttons beside the list, its frame and scroll bar (Blender 3.4).
LIST_MARGIN_UNITS = 4.5
ICON_UNITS = 1.2  # an icon and the gap after it
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


def list_row_width(context=None):
    """Pixels a row of a list (template_list) in a sidebar panel has, with the list's buttons beside it."""
    context = context or bpy.context
    region = context.region
    scale = ui_scale(context)
    width = region.width if region is not None and region.type == 'UI' else DEFAULT_SIDEBAR_PX * scale
    return max(width - LIST_MARGIN_UNITS * 20.0 * scale, 2 * 20.0 * scale)


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
