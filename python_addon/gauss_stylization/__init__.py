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

# Every module, bottom of the import order first: each imports only modules listed before it. The
# sub-packages are jobs, in layers that import one way only (docs/architecture.md, "The add-on";
# tests/python/test_addon_layers.py checks it).
MODULES = (
    "errors", "native",
    "settings.fields", "settings.schema", "settings.versioning", "settings.properties", "settings.settings_io",
    "settings.validation", "settings.paint_curve", "settings.styles",
    "mesh.mesh_io", "mesh.crossings", "mesh.source", "mesh.cache_modifier", "mesh.output", "mesh.recipe_store",
    "mesh.follow_store", "mesh.rest_store",
    "view.viewport", "view.gpu_compat", "view.sidebar",
    "run.run_interface", "run.undo_guard", "run.runs", "run.progress", "run.solver_setup", "run.proxy_run",
    "run.session", "run.targets", "run.pin_targets", "run.live_run", "run.scripted_run", "run.rerun",
    "run.replay", "run.follow",
    "run.modal_events",
    "handles.handles", "handles.handle_tool",
    "sphere.gauss_sphere", "sphere.directions", "sphere.orientation", "sphere.surface", "sphere.sphere_overlay",
    "sphere.style_reach", "sphere.reach_overlay",
    "sphere.sphere_editing", "sphere.style_from_data",
    "bake.pc2", "bake.bake", "bake.bake_operators", "bake.bake_ui", "bake.farm", "bake.batch", "bake.farm_cli",
    "operators", "slot_operators", "crossing_operators", "reach_operators", "ui",
)

import importlib  # noqa: E402

_reloading = "bpy" in locals()  # F8 / script reload: reload the modules too, in that order
for _name in MODULES:
    _module = importlib.import_module("." + _name, __name__)
    if _reloading:
        importlib.reload(_module)

import inspect  # noqa: E402

import bpy  # noqa: E402

from . import (  # noqa: E402
    bake, crossing_operators, handles, operators, reach_operators, run, settings, slot_operators, sphere, ui)
# The modules artists' scripts import by name (docs/scripting.md, docs/baking.md), at the top as before.
from .bake import pc2  # noqa: E402,F401
from .mesh import mesh_io  # noqa: E402,F401
from .run import replay  # noqa: E402,F401
from .settings import settings_io, styles  # noqa: E402,F401

classes = (settings.properties.classes + operators.classes + slot_operators.classes + crossing_operators.classes
           + reach_operators.classes
           + sphere.style_from_data.classes
           + sphere.sphere_editing.classes + bake.bake_operators.classes + ui.classes + bake.bake_ui.classes)


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
    settings.properties.register_pointer()
    settings.versioning.register_handlers()
    run.runs.register_handlers()
    run.follow.register()
    sphere.sphere_overlay.register()
    sphere.reach_overlay.register()
    sphere.sphere_editing.register()
    handles.handle_tool.register()
    bake.farm_cli.register()


def unregister():
    bake.farm_cli.unregister()
    run.follow.unregister()
    run.runs.unregister_handlers()
    settings.versioning.unregister_handlers()
    run.runs.stop_all(bpy.context)  # first: a run's end is told to the event handlers below (on_end)
    handles.handle_tool.unregister()
    sphere.sphere_editing.unregister()
    sphere.reach_overlay.unregister()
    sphere.sphere_overlay.unregister()
    settings.properties.unregister_pointer()
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
