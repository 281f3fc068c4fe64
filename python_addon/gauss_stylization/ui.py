"""Sidebar panels (3D view > Sidebar > Gauss) and the style-slot lists."""

import bpy

from . import native, operators
from .errors import NativeModuleError
from .mesh import output
from .run import runs
from .run.targets import stylize_objects
from .settings import schema, styles
from .settings.fields import Panel
from .view.sidebar import GaussPanel, GaussSubPanel, draw_rows, mesh_object, split_column, wrapped_label


class GAUSS_UL_styles(bpy.types.UIList):
    """Style slots; where their Regions overlap, their weighted strengths add up."""

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
        draw_rows(split_column(layout), obj, obj.gauss_stylization, schema.OBJECT, Panel.MAIN)
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
        tools.operator("object.gauss_style_auto_orient", icon='ORIENTATION_GIMBAL')
        draw_rows(split_column(layout), obj, settings, schema.OBJECT, Panel.SPHERE)
        if not settings.styles:
            wrapped_label(layout, "Stylize adds a %s style" % schema.DEFAULT_PRESET_LABEL, 'INFO')
            return
        col = split_column(layout)
        draw_rows(col, obj, settings, schema.OBJECT, Panel.STYLES)
        slot = styles.active_slot(settings)
        if slot is not None:
            col.separator()
            draw_rows(col, obj, slot, schema.SLOT, Panel.SLOT)


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


classes = (GAUSS_UL_styles, GAUSS_UL_normals,
           VIEW3D_PT_gauss_stylization, VIEW3D_PT_gauss_styles, VIEW3D_PT_gauss_solver)
