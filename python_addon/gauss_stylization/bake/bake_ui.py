"""The Bake sub-panel: bakes to a point cache (bake_operators.py)."""

import bpy

from ..mesh import cache_modifier
from ..settings import schema
from ..settings.fields import Panel
from ..view.sidebar import GaussSubPanel, draw_rows, mesh_object, split_column, wrapped_label  # as every Gauss panel
from . import bake, bake_operators


class VIEW3D_PT_gauss_bake(GaussSubPanel, bpy.types.Panel):
    bl_label = "Bake"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        obj = mesh_object(context)
        settings = obj.gauss_stylization
        layout = self.layout
        draw_rows(split_column(layout), obj, settings, schema.OBJECT, Panel.BAKE)
        if settings.bake_scene_range:
            wrapped_label(layout, "Frames %d to %d (the scene's)" % bake_operators.bake_range(context.scene, settings),
                          'TIME')
        if not settings.bake_filepath:
            where = bake.default_path(obj)
            wrapped_label(layout, "Writes %s" % where, 'FILE_CACHE')
            if not bake.blend_saved():
                wrapped_label(layout, "The .blend file is not saved, so the cache goes to the temporary folder; "
                              "pick a Cache File to keep it elsewhere", 'INFO')
        col = layout.column(align=True)
        col.operator("object.gauss_bake_animation", icon='RENDER_ANIMATION')
        col.operator("object.gauss_bake_progress", icon='SEQUENCE')
        modifier = cache_modifier.find(obj)
        if modifier is not None:
            wrapped_label(layout, "%s plays %s" % (modifier.name, modifier.filepath), 'MODIFIER')


classes = (VIEW3D_PT_gauss_bake,)
