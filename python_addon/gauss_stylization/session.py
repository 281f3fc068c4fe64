"""One stylization run of one object: solver, buffers and output target.

Used by the modal operator (one ``step()`` per timer tick), by the scripted
operator (``step(n)`` once) and by the tick benchmark. Nothing here touches
the UI. Set-up validates everything before the mesh is written, so a failed
start leaves the object as it was.
"""

import time
from collections import namedtuple

import numpy as np

from . import mesh_io, native, output, rest_store, styles
from .validation import SettingsError, check_coordinates, check_object, check_settings

# What a tick compares to decide what to send to the solver. Only lambda and
# the pins need a re-factorization; styles and assignments are cheap to swap.
Applied = namedtuple("Applied", "styles assignment pins lam admm")


def settings_key(settings):
    slots = tuple(
        (slot.preset, slot.sigma, slot.mu, tuple(slot.orientation), slot.axis_contribution,
         tuple(tuple(item.vector) for item in slot.custom_normals))
        for slot in settings.styles)
    assignment = (tuple(slot.vertex_group for slot in settings.styles), settings.uncovered)
    return Applied(slots, assignment, settings.pin_group, settings.lam, settings.admm_iterations)


def ensure_style_slot(settings):
    """An artist must be able to press Stylize right away: add a Cube slot if there is none."""
    if len(settings.styles) == 0:
        slot = settings.styles.add()
        slot.name = "Cube"
        settings.active_style_index = 0
        return True
    return False


class Session:
    def __init__(self, obj):
        self.obj = obj
        self.mesh = obj.data
        self.gauss_core = native.core()
        check_object(obj)
        self.arrays = mesh_io.MeshArrays(self.mesh)
        check_coordinates(obj, self.arrays.coords)
        self.weights = mesh_io.read_group_weights(obj)
        settings = obj.gauss_stylization
        check_settings(obj, settings, self.weights)
        self.target = output.make_target(obj, self.arrays.num_vertices)
        self.applied = settings_key(settings)
        self.solver = self._make_solver(settings)
        # The solver writes its result straight into this buffer every step.
        self.result = np.empty_like(self.arrays.coords)
        self.finite = np.empty(self.result.shape, bool)  # preallocated: a tick allocates nothing
        self.steps = 0
        self.step_ms = []
        self.target.prepare()  # first change to the object: everything above succeeded

    def _make_solver(self, settings):
        pins = styles.pinned_vertices(self.weights, settings.pin_group)
        try:
            solver = self.gauss_core.Solver(
                self.arrays.coords, self.arrays.triangles,
                pinned=pins if len(pins) else None, lam=settings.lam,
                admm_iterations=settings.admm_iterations)
            solver.set_styles(styles.make_styles(self.gauss_core, settings.styles))
            solver.set_face_styles(self._face_styles(settings))
        except (ValueError, TypeError, RuntimeError) as exc:
            raise SettingsError("The solver cannot handle this mesh or setting: %s" % exc) from exc
        return solver

    def _face_styles(self, settings):
        groups = [slot.vertex_group for slot in settings.styles]
        return styles.face_styles(self.arrays, self.weights, groups, settings.uncovered)

    # -- running ---------------------------------------------------------------

    def sync_settings(self):
        """Send changed settings to the solver. Returns None, or why it cannot run now."""
        settings = self.obj.gauss_stylization
        wanted = settings_key(settings)
        if wanted == self.applied:
            return None
        try:
            check_settings(self.obj, settings, self.weights)
            self._apply(settings, wanted)
        except SettingsError as exc:
            return str(exc)
        except (ValueError, TypeError) as exc:
            return "The solver rejected a setting: %s" % exc
        self.applied = wanted
        return None

    def _apply(self, settings, wanted):
        solver, old = self.solver, self.applied
        if wanted.styles != old.styles or wanted.assignment != old.assignment:
            new_styles = styles.make_styles(self.gauss_core, settings.styles)
            faces = self._face_styles(settings)
            # Never let face indices point past the style list, in either order.
            if len(new_styles) >= len(old.styles):
                solver.set_styles(new_styles)
                solver.set_face_styles(faces)
            else:
                solver.set_face_styles(faces)
                solver.set_styles(new_styles)
        if wanted.pins != old.pins:
            solver.set_pins(styles.pinned_vertices(self.weights, settings.pin_group))
        if wanted.lam != old.lam:
            solver.lam = settings.lam
        if wanted.admm != old.admm:
            solver.admm_iterations = settings.admm_iterations

    def step(self, count=1):
        """Run ``count`` solver iterations and write the result to the target."""
        start = time.perf_counter()
        self.solver.step(count)
        self.step_ms.append((time.perf_counter() - start) * 1000.0 / max(count, 1))
        self.steps += count
        self.solver.vertices_into(self.result)
        if not np.isfinite(self.result, out=self.finite).all():  # never write NaN into the artist's mesh
            raise SettingsError("The solver produced invalid positions (the mesh may have "
                                "degenerate faces); try a larger Lambda or fix the mesh")
        self.target.write(self.result)

    # -- ending ----------------------------------------------------------------

    def keep(self):
        """Keep the result; remember the start coordinates for the Reset operator."""
        rest_store.capture(self.mesh, self.arrays.coords, self.target.kind)

    def cancel(self):
        """Put back exactly what was there before the run, as far as it still exists.

        The mesh is restored even when its object was deleted during the run:
        another object may share it, and undo reuses the mesh as it is in memory.
        A freed mesh, or one whose vertex count changed, is left alone.
        """
        if self.mesh_alive():
            self.target.restore()

    def mesh_alive(self):
        try:
            return len(self.mesh.vertices) == self.arrays.num_vertices
        except ReferenceError:  # the mesh was freed (deleted, undo, file load)
            return False

    def object_alive(self):
        try:
            return self.obj.data == self.mesh and self.mesh_alive()
        except ReferenceError:  # the object or mesh was deleted while running
            return False
