"""Gauss Stylization: stylize meshes by preferred face normals.

The add-on is a thin client of the bundled native solver ``gauss_core``:
Blender mesh -> numpy arrays -> solver -> numpy arrays -> mesh.
"""

bl_info = {
    "name": "Gauss Stylization",
    "author": "Gauss Stylization for Blender contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Gauss",
    "description": "Stylize a mesh live by the face normals it should prefer (cube, pyramid, custom...)",
    "category": "Mesh",
}

# Bottom of the import order first: each module imports only modules listed before it.
if "bpy" in locals():  # F8 / script reload: reload the submodules too
    import importlib
    for _module in (errors, native, pc2, fields, schema, properties, mesh_io, source, styles, validation,
                    cache_modifier, output, rest_store, settings_io, handles, undo_guard, runs, progress,
                    solver_setup, session, targets, live_run, scripted_run, viewport, modal_events, directions,
                    orientation, surface, style_from_data, gauss_sphere, gpu_compat, sphere_overlay,
                    sphere_editing, handle_tool, operators, slot_operators, ui, bake, bake_operators, bake_ui):
        importlib.reload(_module)
else:
    from . import (errors, native, pc2, fields, schema, properties, mesh_io, source, styles, validation,
                   cache_modifier, output, rest_store, settings_io, handles, undo_guard, runs, progress,
                   solver_setup, session, targets, live_run, scripted_run, viewport, modal_events, directions,
                   orientation, surface, style_from_data, gauss_sphere, gpu_compat, sphere_overlay,
                   sphere_editing, handle_tool, operators, slot_operators, ui, bake, bake_operators, bake_ui)

import inspect

import bpy

classes = (properties.classes + operators.classes + slot_operators.classes + style_from_data.classes
           + sphere_editing.classes + bake_operators.classes + ui.classes + bake_ui.classes)


def _tooltip_from_docstring(cls):
    """Blender shows a class's docstring as its tooltip verbatim, so the indentation of a
    docstring's second line would show as a stray indent: give it one paragraph instead."""
    doc = cls.__dict__.get("__doc__")
    if doc and "bl_description" not in cls.__dict__:
        cls.bl_description = " ".join(inspect.cleandoc(doc).split())


def register():
    for cls in classes:
        _tooltip_from_docstring(cls)
        bpy.utils.register_class(cls)
    properties.register_pointer()
    runs.register_handlers()
    sphere_overlay.register()
    sphere_editing.register()
    handle_tool.register()


def unregister():
    runs.unregister_handlers()
    runs.stop_all(bpy.context)  # first: a run's end is told to the event handlers below (on_end)
    handle_tool.unregister()
    sphere_editing.unregister()
    sphere_overlay.unregister()
    properties.unregister_pointer()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
