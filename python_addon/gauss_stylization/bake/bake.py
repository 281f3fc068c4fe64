"""Bakes to a point cache (.pc2 played by a Mesh Cache modifier, see cache_modifier.py).

AnimationBake stylizes the evaluated (animated, deformed) mesh of every frame of
a range; ProgressBake records one stylization step by step, the "morph into
style". A bake is advanced a frame at a time (``advance()``), so the operators
can run it synchronously (scripts, background mode) or a frame per timer tick;
then ``finish()`` renames the finished file into place and attaches the
modifier, or ``cancel()`` drops the temporary file and attaches nothing. Either
way the scene frame and the object's cache modifier are as before (the
modifier is off while the bake reads the object, so no bake reads an earlier one).

Warm start (AnimationBake): frame f0 = frame_start is stylized from its rest shape
R_f0 with Script Steps (settings.iterations) steps (0: until converged), exactly as
Stylize would on that frame; every later frame f starts from

    X_f = Y_{f-1} + (R_f - R_{f-1})       (per vertex, object space)

(Y: the previous frame's result, R: the evaluated mesh of a frame, the solver's rest
shape) and runs Bake Steps (settings.bake_steps) steps, so the style carries over
from frame to frame instead of being rebuilt (no flicker). Without warm start
every frame runs Bake Steps steps from its own rest shape: a frame's result does
not depend on the other frames, so ranges can be baked apart and give the same frames.

Warm-up (a farm chunk with warm start, farm.py): the bake starts ``warmup`` frames before
frame_start and writes nothing for them, so its first written frame continues a run of
warmup + 1 frames instead of starting cold; docs/baking.md has how close that comes to one bake.
"""

import os
import tempfile

import bpy

from ..errors import SettingsError
from ..mesh import cache_modifier, source as sources
from ..run.session import Plan, Session
from ..settings import schema
from ..settings.settings_io import to_dict
from . import pc2

DEFAULT_NAME = "%s_gauss.pc2"  # % the object's name made file-safe
DEFAULT_PATH = "//" + DEFAULT_NAME  # next to the .blend file


def temporary_folder():
    """Where a bake of an unsaved file goes by default: Blender's Temporary Files folder
    (Preferences > File Paths), else the system's. Not Blender's session folder, which is
    deleted when Blender quits while the modifier still plays the file."""
    folder = bpy.context.preferences.filepaths.temporary_directory
    return bpy.path.abspath(folder) if folder and os.path.isdir(bpy.path.abspath(folder)) else tempfile.gettempdir()


def blend_saved():
    return bool(bpy.data.filepath)


def default_path(obj):
    """The cache file of ``obj`` when the artist gives none: next to the .blend file, or in the
    temporary folder while the .blend file is not saved."""
    if blend_saved():
        return DEFAULT_PATH % bpy.path.clean_name(obj.name)
    return os.path.join(temporary_folder(), DEFAULT_NAME % bpy.path.clean_name(obj.name))


def resolve_path(filepath, obj):
    """(path as the modifier keeps it, absolute path) for the operator's ``filepath``
    ('' = default_path). Relative paths ('//') the artist gives need a saved .blend file."""
    filepath = filepath or default_path(obj)
    if filepath.startswith("//") and not blend_saved():
        raise SettingsError("Save the .blend file first: the Cache File '%s' is relative to it "
                            "(or clear Cache File to bake to %s)" % (filepath, temporary_folder()))
    absolute = os.path.abspath(bpy.path.abspath(filepath))
    if os.path.isdir(absolute):
        raise SettingsError("The cache path '%s' is a folder; give a file name" % filepath)
    return filepath, absolute


class CacheTarget:
    """A Session target that appends every result to a point cache."""

    kind = 'POINT_CACHE'
    rest = None

    def __init__(self, writer):
        self.writer = writer

    def prepare(self):
        pass

    def write(self, coords):
        self.writer.add(coords)

    def alive(self):
        return True

    def keep(self):
        pass

    def restore(self):
        pass


class WarmUpTarget(CacheTarget):
    """A warm-up frame's target: the result is only carried to the next frame, not written."""

    def write(self, coords):
        pass


class _Bake:
    """What both bakes share: the file, the suspended modifier, the scene frame, the settings."""

    def __init__(self, context, obj, filepath, total):
        self.obj, self.scene = obj, context.scene
        self.modifier_path, self.path = resolve_path(filepath, obj)
        self.total, self.done = total, 0
        self.writer = None
        self.frame = (self.scene.frame_current, self.scene.frame_subframe)
        self.applied = to_dict(self.settings)
        self.suspended = cache_modifier.Suspended(obj).__enter__()

    @property
    def settings(self):
        """Read through the object every time: a kept reference to the settings of an object deleted
        mid-bake reads freed memory (Blender 5.x crashes), the object's raises ReferenceError."""
        return self.obj.gauss_stylization

    def _open(self, points, start):
        self.writer = pc2.Writer(self.path, points, self.total, start=float(start))

    def _check_unchanged(self):
        if to_dict(self.settings) != self.applied:
            raise SettingsError("The settings of '%s' changed during the bake; start it again to bake "
                                "with the new ones" % self.obj.name)

    @property
    def finished(self):
        return self.done >= self.total

    def finish(self, frame_start, last):
        self.writer.commit()
        self._restore()
        cache_modifier.attach(self.obj, self.modifier_path, frame_start, last)

    def cancel(self):
        if self.writer is not None:
            self.writer.discard()
        self._restore()

    def hold(self):
        """The scene frame and the cache modifier as before the bake, while a file is written."""
        self.held = (self.scene.frame_current, self.scene.frame_subframe)
        self.suspended.restore()
        self.scene.frame_current, self.scene.frame_subframe = self.frame

    def resume(self):
        """After the file was written: the bake's frame and suspended modifier back."""
        self.suspended.__enter__()
        self.scene.frame_current, self.scene.frame_subframe = self.held

    def _restore(self):
        self.suspended.restore()
        frame, subframe = self.frame
        try:
            self.scene.frame_set(frame, subframe=subframe)
        except ReferenceError:  # cancelled because another file is being loaded
            pass


class AnimationBake(_Bake):
    def __init__(self, context, obj, frame_start, frame_end, filepath, warm_start, warmup=0):
        """warmup: with warm start, frames baked before frame_start and not written (ignored without)."""
        if frame_end < frame_start:
            raise SettingsError("The last frame (%d) is before the first (%d)" % (frame_end, frame_start))
        if warmup < 0:
            raise SettingsError("Warm-up frames must be 0 or more (got %d)" % warmup)
        super().__init__(context, obj, filepath, frame_end - frame_start + 1)
        self.frame_start, self.warm_start = frame_start, warm_start
        self.warmup = warmup if warm_start else 0
        self.baked = 0  # frames computed, warm-up ones included
        self.previous = None  # (rest, result) of the last baked frame
        try:
            self.scene.frame_set(frame_start - self.warmup)
            self.first = sources.read(obj, True)
            self.first.release()  # only its arrays and weights are needed: later frames share them
            self._open(self.first.arrays.num_vertices, frame_start)
        except BaseException:
            self.cancel()
            raise

    @property
    def next_frame(self):
        """The frame advance() bakes next; before frame_start while warming up."""
        return self.frame_start - self.warmup + self.baked

    @property
    def warming_up(self):
        return self.baked < self.warmup

    def advance(self):
        """Bake the next frame (a warm-up frame, written nowhere, while warming up)."""
        self._check_unchanged()
        frame = self.next_frame
        source = self.first
        if self.baked:
            self.scene.frame_set(frame)
            depsgraph = bpy.context.evaluated_depsgraph_get()
            source = self.first.moved(sources.evaluated_coords(self.obj, depsgraph, self.first.arrays,
                                                               "at frame %d" % frame))
        target = WarmUpTarget(None) if self.warming_up else CacheTarget(self.writer)
        session = Session(Plan(self.obj, source, target))
        steps = self.settings.bake_steps
        if self.warm_start:
            if self.previous is None:
                steps = self.settings.iterations
            else:
                rest, result = self.previous
                session.start_from(result + (source.arrays.coords - rest))
        if steps == 0:  # Script Steps 0: until converged, as Stylize runs it
            session.step_until(schema.UNTIL_CONVERGED_CAP)
        else:
            session.step(steps)
        if self.warm_start:
            self.previous = (source.arrays.coords, session.result.copy())
        if not self.warming_up:
            self.done += 1
        self.baked += 1

    def finish(self):
        super().finish(self.frame_start, last=True)


class ProgressBake(_Bake):
    def __init__(self, context, obj, steps, steps_per_frame, frame_start, filepath):
        if steps_per_frame < 1 or steps % steps_per_frame:
            raise SettingsError("Steps (%d) must be a multiple of Steps per Frame (%d)" % (steps, steps_per_frame))
        super().__init__(context, obj, filepath, steps // steps_per_frame + 1)
        self.frame_start, self.steps_per_frame = frame_start, steps_per_frame
        try:
            source = sources.read(obj, self.settings.use_modifiers)
            rest = source.arrays.coords
            self._open(source.arrays.num_vertices, frame_start)
            self.session = Session(Plan(obj, source, CacheTarget(self.writer)))
            self.writer.add(rest)  # frame 0: before the first step
            self.done = 1
        except BaseException:
            self.cancel()
            raise

    def advance(self):
        """Run the next frame's steps."""
        self._check_unchanged()
        self.session.step(self.steps_per_frame)
        self.done += 1

    def finish(self):
        # The cache holds what was stylized: the stack's output (last) or the base mesh (first).
        super().finish(self.frame_start, last=self.settings.use_modifiers)
