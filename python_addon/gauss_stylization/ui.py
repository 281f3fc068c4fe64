"""Sidebar panels (3D view > Sidebar > Gauss) and the style-slot lists."""

import bpy
from bpy.props import StringProperty

from . import native, operators
from .errors import NativeModuleError
from .mesh import output
from .run import follow, replay, runs
from .run.targets import stylize_objects
from .settings import schema, styles
from .settings.fields import Panel
from .view.sidebar import (ICON_UNITS, GaussPanel, GaussSubPanel, draw_rows, list_row_width, mesh_object,
                           split_column, text_width, ui_scale, wrapped_label)


def slot_row(slot, width, measure, unit):
    """(factor, region text) of a slot's row ``width`` pixels wide (``unit``: Blender's UI unit in
    pixels): the name gets the row, with its Region's icon; the Region's name (its vertex group, or
    "All": the whole mesh) too where both fit (factor: the name's share of the row), else (None, None).
    In two halves of the default sidebar, "Stretched Cube" was cut to "Stretch..."."""
    region = slot.vertex_group or "All"
    name_px, region_px = measure(slot.name), measure(region)
    spare = width - ICON_UNITS * unit - name_px - region_px
    if spare < 2 * unit:  # each text keeps a little padding
        return None, None
    return (ICON_UNITS * unit + name_px + spare / 2.0) / width, region


class GAUSS_UL_styles(bpy.types.UIList):
    """Style slots; where their Regions overlap, their weighted strengths add up."""

    def draw_item(self, context, layout, data, slot, icon, active_data, active_propname, index):
        icon = 'GROUP_VERTEX' if slot.vertex_group else 'MESH_DATA'  # the slot's Region
        factor, region = slot_row(slot, list_row_width(context), text_width, 20.0 * ui_scale(context))
        if region is None:
            layout.prop(slot, "name", text="", emboss=False, icon=icon)
            return
        split = layout.split(factor=factor)
        split.prop(slot, "name", text="", emboss=False, icon=icon)
        split.label(text=region)


NORMAL_NUMBER_SHARE = 0.16  # of a normal's row, for its number (up to "20" at the default width)


def normal_text(vector):
    """"-0.79 -0.19 0.58": one label, so that its numbers cannot run together (in three labels of a
    third of the row each, a minus sign filled the gap before it)."""
    return " ".join("%.2f" % value for value in vector)


class GAUSS_UL_normals(bpy.types.UIList):
    """Custom normals, one row each: its number, then X Y Z to two decimals (number fields would be
    too narrow to read in the sidebar). The active one is edited under the list and highlighted on
    the Gauss sphere."""

    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        split = layout.split(factor=NORMAL_NUMBER_SHARE)
        split.label(text="%d" % (index + 1))
        split.label(text=normal_text(item.vector))


class VIEW3D_PT_gauss_stylization(GaussPanel, bpy.types.Panel):
    bl_label = "Gauss Stylization"

    def draw(self, context):
        layout = self.layout
        try:
            native.core()
        except NativeModuleError as exc:
            wrapped_label(layout, str(exc), 'ERROR')
        for run in runs.live_runs():
            _draw_run_state(layout, run)
        obj = mesh_object(context)
        if obj is not None and runs.session_of(obj) is not None:
            _draw_paint_switch(layout, context)
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
        if replay.problem(obj) is None:  # kept runs to replay
            layout.operator("object.gauss_replay", icon='FILE_REFRESH')
        draw_rows(split_column(layout), obj, obj.gauss_stylization, schema.OBJECT, Panel.MAIN)
        for line in follow.panel_lines(obj):
            wrapped_label(layout, line, 'FILE_REFRESH')
        note = output.refusal_before_run(obj, context.view_layer.depsgraph)
        if note:
            wrapped_label(layout, note, 'ERROR')


class VIEW3D_PT_gauss_styles(GaussSubPanel, bpy.types.Panel):
    bl_label = "Styles"

    def draw(self, context):
        obj = mesh_object(context)
        settings = obj.gauss_stylization
        layout = self.layout
        draw_rows(split_column(layout), obj, settings, schema.OBJECT, Panel.METHOD)
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
        tools.operator("object.gauss_style_from_gauss_map", icon='SPHERE')
        tools.operator("object.gauss_style_auto_orient", icon='ORIENTATION_GIMBAL')
        draw_rows(split_column(layout), obj, settings, schema.OBJECT, Panel.SPHERE)
        if settings.show_style_reach:
            reach = layout.column(align=True)
            reach.operator("object.gauss_select_unreached", icon='RESTRICT_SELECT_OFF')
            reach.operator("object.gauss_store_style_angles", icon='GROUP_VERTEX')
        if not settings.styles:
            wrapped_label(layout, "Stylize adds a %s style" % schema.DEFAULT_PRESET_LABEL, 'INFO')
            return
        col = split_column(layout)
        draw_rows(col, obj, settings, schema.OBJECT, Panel.STYLES)
        slot = styles.active_slot(settings)
        if slot is not None:
            col.separator()
            draw_rows(col, obj, slot, schema.SLOT, Panel.SLOT)
            look = schema.look_lambda(slot.preset)
            if look is not None and not schema.is_cubic(settings) and settings.lam < 0.5 * look:
                wrapped_label(layout, "%s shows from Lambda about %g (Solver panel)"
                              % (schema.style_label(slot.preset), look), 'INFO')


class OBJECT_OT_gauss_run_details(bpy.types.Operator):
    """A row of the live run's box whose numbers are in its tooltip ("settling, 80%": how far the last
    step moved the mesh, against the Tolerance); a click writes them to the Info log"""
    bl_idname = "object.gauss_run_details"
    bl_label = "Run Details"
    bl_options = {'INTERNAL'}  # not registered: a live run counts registered operators as edits

    details: StringProperty(options={'HIDDEN', 'SKIP_SAVE'})

    @classmethod
    def description(cls, context, properties):
        return properties.details

    def execute(self, context):
        self.report({'INFO'}, self.details)
        return {'FINISHED'}


def _draw_run_state(layout, run):
    """What a live run (a Stylize, or a bake: bake_operators.py) does: its objects and how far
    they are, and the keys that end it. A row with details shows them as its tooltip."""
    title, lines, hints = run.panel_state()
    box = layout.box().column(align=True)
    box.label(text=title, icon='TIME')
    for text, icon, *details in lines:
        if details:
            row = box.row()
            row.alignment = 'LEFT'  # as the labels around it
            row.operator(OBJECT_OT_gauss_run_details.bl_idname, text=text, icon=icon,
                         emboss=False).details = details[0]
        else:
            wrapped_label(box, text, icon)
    for hint in hints:
        wrapped_label(box, hint)


def _draw_paint_switch(layout, context):
    """During a live run: to Weight Paint with the active style's Region, and back (the mode menu
    and Ctrl+Tab do the same)."""
    if context.mode == 'PAINT_WEIGHT':
        layout.operator("object.gauss_paint_region", text="Back to Object Mode", icon='OBJECT_DATAMODE')
    else:
        layout.operator("object.gauss_paint_region", icon='BRUSH_DATA')


class VIEW3D_PT_gauss_solver(GaussSubPanel, bpy.types.Panel):
    bl_label = "Solver"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        obj = mesh_object(context)
        draw_rows(split_column(self.layout), obj, obj.gauss_stylization, schema.OBJECT, Panel.SOLVER)
        # Next to Avoid Self-Intersections: check a result (or an input) for a print, with it or without.
        self.layout.operator("object.gauss_select_intersections", icon='SELECT_INTERSECT')
        session = runs.session_of(obj)
        if session is not None and len(session.held_anywhere):  # where the guard has held the live run
            self.layout.operator("object.gauss_select_held", icon='RESTRICT_SELECT_OFF')


classes = (OBJECT_OT_gauss_run_details, GAUSS_UL_styles, GAUSS_UL_normals,
           VIEW3D_PT_gauss_stylization, VIEW3D_PT_gauss_styles, VIEW3D_PT_gauss_solver)
