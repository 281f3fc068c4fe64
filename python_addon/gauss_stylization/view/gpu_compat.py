"""Drawing with the `gpu` module in every Blender the add-on supports (3.4 to 4.x; no bgl).

Built-in shader names changed: 3.x has '3D_UNIFORM_COLOR' and friends (3.4 also
accepts the new names), 4.0 removed the '2D_'/'3D_' prefixes, and 4.1+ adds
'POINT_UNIFORM_COLOR', which draws round points sized by its 'size' uniform; the
older shaders draw square points sized by gpu.state.point_size_set (set for both). Positions are
always given as 3-vectors (z = 0 for pixels), which every version's shaders take.
"""

import bpy
import gpu
import numpy as np
from gpu_extras.batch import batch_for_shader

# Kind -> names to try, newest first.
_NAMES = {
    "uniform": ("UNIFORM_COLOR", "3D_UNIFORM_COLOR"),
    "smooth": ("SMOOTH_COLOR", "3D_SMOOTH_COLOR"),
    "points": ("POINT_UNIFORM_COLOR", "UNIFORM_COLOR", "3D_UNIFORM_COLOR"),
}
_shaders = {}


def shader(kind):
    """The built-in shader for ``kind`` ('uniform', 'smooth', 'points') and its name."""
    if kind not in _shaders:
        for name in _NAMES[kind]:
            try:
                _shaders[kind] = (gpu.shader.from_builtin(name), name)
                break
            except (ValueError, TypeError):  # not a shader of this Blender
                continue
        else:
            raise RuntimeError("no built-in shader for %s among %s" % (kind, _NAMES[kind]))
    return _shaders[kind]


def _positions(points):
    points = np.asarray(points, np.float32)
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points), np.float32)])
    return points


def triangles_batch(points, colours, indices=None):
    """A batch of smooth-coloured triangles to draw with draw_batch() as often as needed (building one
    uploads every corner: keep it while the triangles stay). points: N by 2 or 3; colours: N by 4;
    indices: M by 3 or None."""
    program, _ = shader("smooth")
    return batch_for_shader(program, 'TRIS', {"pos": _positions(points), "color": np.asarray(colours, np.float32)},
                            indices=None if indices is None else np.asarray(indices, np.int32))


def draw_batch(batch):
    """Draw a triangles_batch()."""
    program, _ = shader("smooth")
    program.bind()
    batch.draw(program)


def draw_triangles(points, colours, indices=None):
    """Smooth-coloured triangles, uploaded for this drawing only. points: N by 2 or 3; colours: N by 4;
    indices: M by 3 or None."""
    draw_batch(triangles_batch(points, colours, indices))


def draw_uniform(points, colour, primitive='TRIS'):
    """Triangles or lines of one colour. points: N by 2 or 3."""
    program, _ = shader("uniform")
    batch = batch_for_shader(program, primitive, {"pos": _positions(points)})
    program.bind()
    program.uniform_float("color", colour)
    batch.draw(program)


def draw_points(points, colour, size):
    """Points of one colour, ``size`` pixels across. points: N by 2 or 3."""
    if not len(points):
        return
    program, name = shader("points")
    batch = batch_for_shader(program, 'POINTS', {"pos": _positions(points)})
    program.bind()
    program.uniform_float("color", colour)
    if name == "POINT_UNIFORM_COLOR":  # its documented 'size' uniform; the state below as well
        try:
            program.uniform_float("size", size)
        except ValueError:  # a build whose point shader reads only the state
            pass
    gpu.state.point_size_set(size)
    batch.draw(program)
    gpu.state.point_size_set(1.0)


def saved_state():
    """The blend mode and depth test now, as restore_state() takes them (None where this
    Blender cannot read one back)."""
    blend = gpu.state.blend_get() if hasattr(gpu.state, "blend_get") else None
    depth = gpu.state.depth_test_get() if hasattr(gpu.state, "depth_test_get") else None
    return blend, depth


def restore_state(state):
    """Put back what saved_state() read; without a getter, blending off (Blender's own default
    for draw handlers) and the depth test left alone."""
    blend, depth = state
    gpu.state.blend_set(blend or 'NONE')
    if depth is not None:
        gpu.state.depth_test_set(depth)


class ViewDrawHandler:
    """A draw handler of every 3D view's main region, added and removed once.

    ``draw()`` runs at ``stage`` ('POST_VIEW': world space, 'POST_PIXEL': region pixels). Blender
    and other add-ons draw after it with the state it leaves, so the blend mode and depth test
    are put back as they were, also when it fails. An exception in it would be printed at every
    redraw, so each distinct one is printed once (named after ``title``)."""

    def __init__(self, title, draw, stage):
        self.title, self.draw, self.stage = title, draw, stage
        self.handle = None
        self.failures = set()

    def _run(self):
        state = saved_state()
        try:
            self.draw()
        except Exception as exc:
            message = "%s: %s" % (type(exc).__name__, exc)
            if message not in self.failures:
                self.failures.add(message)
                print("%s: %s" % (self.title, message))
        finally:
            restore_state(state)

    def add(self):
        if self.handle is None:
            self.handle = bpy.types.SpaceView3D.draw_handler_add(self._run, (), 'WINDOW', self.stage)

    def remove(self):
        if self.handle is not None:
            bpy.types.SpaceView3D.draw_handler_remove(self.handle, 'WINDOW')
            self.handle = None
