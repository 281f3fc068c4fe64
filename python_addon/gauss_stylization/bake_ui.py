"""The Bake sub-panel: bakes to a point cache (bake_operators.py)."""

import bpy

from . import cache_modifier, schema
from .fields import Panel
# The sidebar's own sub-panel mix-in and row drawing, so this panel looks and behaves like the others.
from .ui import _GaussSubPanel as GaussSubPanel, _draw_rows as draw_rows, _mesh_object as mesh_object, \
    _split_column as split_column


class VIEW3D_PT_gauss_bake(GaussSubPanel, bpy.types.Panel):
    bl_label = "Bake"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        obj = mesh_object(context)
        layout = self.layout
        draw_rows(split_column(layout), obj, obj.gauss_stylization, schema.OBJECT, Panel.BAKE)
        col = layout.column(align=True)
        col.operator("object.gauss_bake_animation", icon='RENDER_ANIMATION')
        col.operator("object.gauss_bake_progress", icon='SEQUENCE')
        modifier = cache_modifier.find(obj)
        if modifier is not None:
            layout.label(text="Plays %s" % modifier.filepath, icon='FILE_CACHE')


classes = (VIEW3D_PT_gauss_bake,)
