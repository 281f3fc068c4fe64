"""Farm jobs of an animation bake (docs/baking.md, "On a render farm"): one chunk of frames baked
by one worker, and the chunks merged into the cache one bake of the whole range writes.

A chunk takes every setting from the object in the opened .blend (so every worker bakes the same
thing); only its frames and its file are given. With Warm Start it first bakes the object's Farm
Warm-up frames before its first frame (never before the shot's first frame, from which one bake
starts), writing nothing for them (bake.AnimationBake's warmup). Every baked frame prints a line, so
a farm's task timeout sees the job alive.
"""

import glob
import os
import re
import time

import bpy

from ..errors import SettingsError
from ..run.session import ensure_style_slot
from ..run.targets import stylize_problem
from . import bake, pc2
from .bake_operators import bake_range

PREFIX = "gauss_bake"  # every line the farm jobs print starts with it (and the command's name)


def say(text):
    print("%s: %s" % (PREFIX, text), flush=True)


_RUN = re.compile(r"\s*(-?\d+)\s*(?:(?:-|\.\.)\s*(-?\d+)\s*)?")


def parse_frames(text):
    """One range of frames -> (A, B): 'A-B', 'A..B' (Blender's way), 'A', or a comma list of these that
    joins into one range without gaps ('47,48': how Flamenco's frameChunker writes a chunk of two
    frames). Frames may be negative ('-10--1')."""
    runs = []
    for part in text.split(","):
        match = _RUN.fullmatch(part)
        if match is None:
            raise SettingsError("Frames must be A-B (e.g. 1-48), got '%s'" % text)
        first = int(match.group(1))
        last = int(match.group(2)) if match.group(2) is not None else first
        if last < first:
            raise SettingsError("The last frame (%d) is before the first (%d)" % (last, first))
        runs.append((first, last))
    runs.sort()
    # Blender clamps the scene's frame to its range: a frame beyond it would bake the last one again.
    frame = bpy.types.Scene.bl_rna.properties["frame_current"]
    if runs[0][0] < frame.hard_min or max(last for _first, last in runs) > frame.hard_max:
        raise SettingsError("Blender's frames are %d to %d, got '%s'" % (frame.hard_min, frame.hard_max, text))
    end = runs[0][1]
    for first, last in runs[1:]:
        if first > end + 1:
            raise SettingsError("Frames %s are not one range: frame %d is missing (a chunk bakes frames "
                                "without gaps)" % (text, end + 1))
        end = max(end, last)
    return runs[0][0], end


def mesh_object(name):
    obj = bpy.data.objects.get(name)
    if obj is None:
        meshes = sorted(o.name for o in bpy.data.objects if o.type == 'MESH')
        raise SettingsError("No object '%s' in %s (its meshes: %s)"
                            % (name, bpy.data.filepath or "the open file", ", ".join(meshes) or "none"))
    if obj.type != 'MESH':
        raise SettingsError("'%s' is not a mesh object (its type is %s)" % (name, obj.type))
    return obj


def warmup_frames(scene, settings, first):
    """Frames a chunk starting at ``first`` bakes before it: the object's Warm-up with Warm Start
    (none without), but none before the shot's first frame, where one bake starts cold too."""
    if not settings.bake_warm_start:
        return 0
    shot_start = bake_range(scene, settings)[0]
    return max(0, min(settings.bake_warmup_frames, first - shot_start))


def bake_chunk(name, first, last, out):
    """Bake frames first..last of object ``name`` to the .pc2 ``out`` with the object's settings.
    Raises SettingsError (and the bake's own errors) with a message for the artist."""
    obj = mesh_object(name)
    context = bpy.context
    if context.view_layer.objects.get(obj.name) is None:
        raise SettingsError("'%s' is not in the scene's view layer '%s'" % (name, context.view_layer.name))
    context.view_layer.objects.active = obj
    problem = stylize_problem(context)
    if problem:
        raise SettingsError(problem)
    settings = obj.gauss_stylization
    if ensure_style_slot(settings):  # as Bake Animation does; the worker does not save the file
        say("'%s' has no style slot: baking with a %s style" % (name, settings.styles[0].name))
    warm_start = settings.bake_warm_start
    warmup = warmup_frames(context.scene, settings, first)
    job = bake.AnimationBake(context, obj, first, last, out, warm_start, warmup)
    say("'%s' frames %d-%d, %s -> %s" % (
        name, first, last, "warm start, %d warm-up frames from %d" % (warmup, first - warmup) if warm_start
        else "no warm start (frames independent)", job.path))
    started = time.perf_counter()
    try:
        while not job.finished:
            frame, warming = job.next_frame, job.warming_up
            tick = time.perf_counter()
            job.advance()
            took = time.perf_counter() - tick
            if warming:
                say("frame %d: warm-up %d/%d (%.2f s)" % (frame, job.baked, warmup, took))
            else:
                say("frame %d: %d/%d (%.2f s)" % (frame, job.done, job.total, took))
        job.finish()
    except BaseException:
        job.cancel()
        raise
    say("wrote %s: %d frames in %.1f s" % (job.path, job.total, time.perf_counter() - started))
    return job.path


def expand(patterns):
    """Chunk paths as given, or as a glob matches them when the shell did not (a farm's command line)."""
    paths = []
    for pattern in patterns:
        if os.path.exists(pattern) or not glob.has_magic(pattern):
            paths.append(pattern)
            continue
        matched = sorted(glob.glob(pattern))
        if not matched:
            raise SettingsError("No file matches %s" % pattern)
        paths += matched
    return paths


def merge_chunks(patterns, out, frames=None):
    """Merge the chunks into ``out``; frames: (first, last) the chunks must cover exactly, or None."""
    paths = expand(patterns)
    for path in paths:
        if os.path.isdir(path):
            raise SettingsError("'%s' is a folder, not a .pc2 chunk" % path)
    if os.path.isdir(out):
        raise SettingsError("The output '%s' is a folder; give a file name" % out)
    try:
        if frames is not None:
            heads = [pc2.header(path) for path in paths]
            start = min(head[1] for head in heads)
            end = max(head[1] + (head[3] - 1) * head[2] for head in heads)
            if (start, end) != frames:
                raise SettingsError("The chunks hold frames %g-%g, not %d-%d: a chunk is missing or left from "
                                    "another bake" % (start, end, frames[0], frames[1]))
        start, samples = pc2.merge(paths, out)
    except FileNotFoundError as exc:
        raise SettingsError("No chunk %s" % exc.filename) from None
    say("merged %d chunks: frames %g-%g -> %s" % (len(paths), start, start + samples - 1, os.path.abspath(out)))
    return out
