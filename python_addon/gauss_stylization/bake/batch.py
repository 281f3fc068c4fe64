"""Stylization of a batch of files (docs/baking.md, "A batch of files"): every .obj or .blend of a
list with the settings of a saved preset, one output per input.

A preset is the JSON settings_io.to_json writes for an object (or any part of it: what it leaves
out keeps the file's or the default value); one written whole by an earlier version is read as it was
written (versioning.as_saved). An .obj is imported into an empty file, stylized into
its own mesh and exported as '<name>_gauss.obj'; a .blend is opened, its meshes (or the one named)
stylized with the preset as its Output says, and saved as '<name>_gauss.blend'. A file that cannot
be read or stylized is reported and skipped; the batch goes on with the next.
"""

import json
import os
import time

import bpy

from ..errors import NativeModuleError, SettingsError
from ..run.session import ensure_style_slot
from ..run.targets import stylize_problem
from ..settings import schema
from ..settings.settings_io import apply_dict
from ..settings.versioning import as_saved
from .farm import mesh_object, say

SUFFIX = "_gauss"
KINDS = (".obj", ".blend")
_FILE_ERRORS = (SettingsError, NativeModuleError, RuntimeError, OSError, ValueError, KeyError, TypeError)


def read_preset(path):
    """The settings dict of a preset file; SettingsError naming what is wrong with it."""
    try:
        with open(path, encoding="utf-8") as handle:
            preset = json.load(handle)
    except (OSError, ValueError) as exc:
        raise SettingsError("Cannot read the preset %s: %s" % (path, exc)) from None
    if not isinstance(preset, dict):
        raise SettingsError("The preset %s is not a JSON object of settings" % path)
    unknown = sorted(set(preset) - {field.name for field in schema.OBJECT})
    if unknown:
        raise SettingsError("The preset %s has unknown settings: %s" % (path, ", ".join(unknown)))
    return as_saved(preset)  # a whole preset saved by an earlier version gives what it gave then


def _open_obj(path):
    """The meshes of an .obj, imported into an empty file, stylized into themselves."""
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.wm.obj_import(filepath=path)
    objects = sorted((obj for obj in bpy.data.objects if obj.type == 'MESH'), key=lambda obj: obj.name)
    if not objects or not any(len(obj.data.polygons) for obj in objects):
        raise SettingsError("no faces in it")
    return objects


def _open_blend(path, name):
    bpy.ops.wm.open_mainfile(filepath=path)
    if bpy.context.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    if name:
        return [mesh_object(name)]
    layer = bpy.context.view_layer
    objects = sorted((obj for obj in layer.objects if obj.type == 'MESH' and obj.visible_get()),
                     key=lambda obj: obj.name)
    if not objects:
        raise SettingsError("no visible mesh object in it")
    return objects


def _stylize(objects, preset, force_mesh_output):
    for obj in objects:
        apply_dict(obj.gauss_stylization, preset)
        if force_mesh_output:
            obj.gauss_stylization.output = 'MESH'
        ensure_style_slot(obj.gauss_stylization)
    layer = bpy.context.view_layer
    for obj in layer.objects:
        obj.select_set(obj in objects)
    layer.objects.active = objects[0]
    problem = stylize_problem(bpy.context)
    if problem:
        raise SettingsError(problem)
    # An error the operator reports comes back as a RuntimeError carrying its message.
    if bpy.ops.object.gauss_stylize() != {'FINISHED'}:
        raise SettingsError("Stylize did not finish")


def output_path(path, out_dir, taken):
    """'<out_dir>/<name>_gauss<ext>', numbered when two inputs share a name."""
    stem, ext = os.path.splitext(os.path.basename(path))
    candidate, number = os.path.join(out_dir, stem + SUFFIX + ext.lower()), 1
    while candidate in taken:
        number += 1
        candidate = os.path.join(out_dir, "%s%s_%d%s" % (stem, SUFFIX, number, ext.lower()))
    taken.add(candidate)
    return candidate


def stylize_file(path, preset, out, name=None):
    """Stylize one file into ``out`` (see the module's doc); raises on a bad file."""
    if not os.path.isfile(path):
        raise SettingsError("no such file")
    kind = os.path.splitext(path)[1].lower()
    if kind == ".obj":
        objects = _open_obj(path)
        _stylize(objects, preset, force_mesh_output=True)
        for obj in bpy.data.objects:
            obj.select_set(obj in objects)
        bpy.ops.wm.obj_export(filepath=out, export_selected_objects=True, export_materials=False)
    elif kind == ".blend":
        objects = _open_blend(path, name)
        _stylize(objects, preset, force_mesh_output=False)
        bpy.ops.wm.save_as_mainfile(filepath=out, copy=True)
    else:
        raise SettingsError("not a %s file" % " or ".join(KINDS))
    return [obj.name for obj in objects]


def run(paths, preset_path, out_dir, name=None):
    """Stylize every file of ``paths``; returns (outputs, skipped [(path, reason)])."""
    preset = read_preset(preset_path)
    os.makedirs(out_dir, exist_ok=True)
    outputs, skipped, taken = [], [], set()
    started = time.perf_counter()
    for number, path in enumerate(paths, 1):
        path = os.path.abspath(path)
        out = output_path(path, os.path.abspath(out_dir), taken)
        tick = time.perf_counter()
        try:
            names = stylize_file(path, preset, out, name)
        except _FILE_ERRORS as exc:
            skipped.append((path, str(exc).strip() or type(exc).__name__))
            say("file %d/%d: SKIPPED %s: %s" % (number, len(paths), path, skipped[-1][1]))
            continue
        outputs.append(out)
        say("file %d/%d: %s (%s) -> %s (%.2f s)" % (number, len(paths), path, ", ".join(names), out,
                                                    time.perf_counter() - tick))
    say("batch: %d stylized, %d skipped in %.1f s" % (len(outputs), len(skipped), time.perf_counter() - started))
    return outputs, skipped
