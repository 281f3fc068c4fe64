"""The Mesh Cache modifier that plays a bake back (Blender's own reader of .pc2 files).

One modifier per object, found by its name: a new bake updates it. It replaces
the vertex positions of the mesh at its place in the stack by the cached ones
(deform mode Overwrite, influence 1), cache frame i at scene frame
``frame_start + i`` (time mode Frame: the file's own start frame and rate are
not read), axes as stored (forward +Y, up +Z, no flip: Blender's object space).
At integer frames Blender reads one cached frame without blending, so playback
shows the baked coordinates exactly.

Where it goes: a bake of the evaluated mesh holds the stack's output, so the
modifier goes last; a bake of the base mesh holds positions of the base
vertices, so it goes first and the other modifiers apply on top.
"""

import bpy

NAME = "Gauss Bake"
OLD_NAMES = ("Gauss Stylized Cache",)  # what files saved by earlier versions call it


def find(obj):
    """The object's cache modifier (by its name, or a name earlier versions gave it), or None."""
    for name in (NAME,) + OLD_NAMES:
        modifier = obj.modifiers.get(name)
        if modifier is not None and modifier.type == 'MESH_CACHE':
            return modifier
    return None


class Suspended:
    """Context: the object's cache modifier (if any) is off in the viewport, so the evaluated
    mesh is what the bake reads, not the previous bake. Restored on exit."""

    def __init__(self, obj):
        # The modifier is found through the object each time: a kept reference to the modifier of an
        # object deleted meanwhile reads freed memory (Blender 5.x crashes), the object's raises
        # ReferenceError.
        self.obj = obj
        modifier = find(obj)
        self.shown = modifier.show_viewport if modifier is not None else None

    @property
    def modifier(self):
        return find(self.obj) if self.shown is not None else None

    def __enter__(self):
        modifier = self.modifier
        if modifier is not None and self.shown:
            modifier.show_viewport = False
        return self

    def __exit__(self, *_exc):
        self.restore()
        return False

    def restore(self):
        try:
            modifier = self.modifier
            if modifier is not None and modifier.show_viewport != self.shown:
                modifier.show_viewport = self.shown
        except ReferenceError:  # removed with its object meanwhile
            pass


def attach(obj, filepath, frame_start, last):
    """Add or update the cache modifier of ``obj`` to play ``filepath`` from ``frame_start``;
    ``last``: at the end of the stack (else first). Returns the modifier."""
    modifier = find(obj)
    if modifier is None:
        modifier = obj.modifiers.new(NAME, 'MESH_CACHE')
    modifier.name = NAME  # one saved by an earlier version takes today's name when it is baked again
    modifier.cache_format = 'PC2'
    modifier.filepath = filepath
    modifier.deform_mode = 'OVERWRITE'
    modifier.factor = 1.0
    modifier.interpolation = 'LINEAR'
    modifier.play_mode = 'SCENE'
    modifier.time_mode = 'FRAME'
    modifier.frame_start = frame_start
    modifier.frame_scale = 1.0
    modifier.forward_axis = 'POS_Y'
    modifier.up_axis = 'POS_Z'
    # No flip: a set of axes in Blender 3.4, three booleans in 4.2 and later.
    flip = modifier.bl_rna.properties["flip_axis"]
    modifier.flip_axis = set() if flip.type == 'ENUM' else (False,) * flip.array_length
    modifier.show_viewport = modifier.show_render = True
    _move(obj, modifier, len(obj.modifiers) - 1 if last else 0)
    obj.update_tag()  # the file may have been replaced under the same name
    return modifier


def _move(obj, modifier, index):
    current = list(obj.modifiers).index(modifier)
    if current == index:
        return
    move = getattr(obj.modifiers, "move", None)  # Blender 4.x
    if move is not None:
        move(current, index)
        return
    with bpy.context.temp_override(object=obj, active_object=obj):  # Blender 3.4
        bpy.ops.object.modifier_move_to_index(modifier=modifier.name, index=index)


def remove(obj):
    """Drop the cache modifier from ``obj`` (a copy of a baked object must not replay the bake)."""
    modifier = find(obj)
    if modifier is not None:
        obj.modifiers.remove(modifier)
