"""One stylization run of one object: solver, buffers and output target.

Used by the modal operator (one ``step()`` per timer tick), by the scripted
operator (``step(n)`` once) and by the tick benchmark. Nothing here touches
the UI. Set-up validates everything before the mesh is written, so a failed
start leaves the object as it was.
"""

import time

import numpy as np

from . import native, output, rest_store, schema, source as sources, styles
from .errors import SettingsError
from .fields import Live, changes
from .settings_io import add_slot, to_dict
from .validation import check_coordinates, check_object, check_settings

def ensure_style_slot(settings):
    """An artist must be able to press Stylize right away: add a slot of the default preset
    if there is none. True if one was added."""
    if len(settings.styles) == 0:
        add_slot(settings, {"preset": schema.DEFAULT_PRESET})
        settings.active_style_index = 0
        return True
    return False


class Session:
    """source: what to stylize (source.Source; default: read from ``obj`` by its Use Modifiers);
    target: where results go (default: ``obj``'s Output, output.make_target)."""

    def __init__(self, obj, source=None, target=None):
        self.obj = obj
        self.mesh = obj.data
        self.gauss_core = native.core()
        check_object(obj)
        settings = obj.gauss_stylization
        if source is None:
            source = sources.read(obj, settings.use_modifiers)
        try:
            self.arrays = source.arrays
            check_coordinates(obj, self.arrays.coords)
            self.weights = source.weights
            check_settings(obj, settings, self.weights)
            self.target = target or output.make_target(obj, source)
            # The settings the solver runs with (settings_io.to_dict); a tick compares them
            # with the panel's to find what changed, and each change does what its field's
            # Live says (schema.py): so no setting can be missed.
            self.applied = to_dict(settings)
            self.solver = self._make_solver(settings)
            # The solver writes its result straight into this buffer every step.
            self.result = np.empty_like(self.arrays.coords)
            self.finite = np.empty(self.result.shape, bool)  # preallocated: a tick allocates nothing
            self.steps = 0
            self.step_ms = []
            self.target.prepare()  # first change to the object: everything above succeeded
        finally:
            source.release()  # the evaluated copy, unless the target took it over

    def _make_solver(self, settings):
        pins = styles.pinned_vertices(self.weights, settings.pin_group)
        try:
            solver = self.gauss_core.Solver(
                self.arrays.coords, self.arrays.triangles, pinned=pins if len(pins) else None,
                **{field.name: field.read(settings) for field in schema.SOLVER_SETTERS})
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
        wanted = to_dict(settings)
        changed = changes(schema.OBJECT, self.applied, wanted)
        if changed:
            try:
                check_settings(self.obj, settings, self.weights)
                self._apply(settings, changed)
            except SettingsError as exc:
                return str(exc)
            except (ValueError, TypeError) as exc:
                return "The solver rejected a setting: %s" % exc
        self.applied = wanted
        return None

    def _apply(self, settings, changed):
        solver = self.solver
        new_styles = faces = None
        if Live.STYLES in changed:
            new_styles = styles.make_styles(self.gauss_core, settings.styles)
        if Live.REGIONS in changed:
            faces = self._face_styles(settings)
        # Never let face indices point past the style list, in either order.
        if new_styles is not None and len(new_styles) >= len(self.applied["styles"]):
            solver.set_styles(new_styles)
            new_styles = None
        if faces is not None:
            solver.set_face_styles(faces)
        if new_styles is not None:
            solver.set_styles(new_styles)
        if Live.PINS in changed:
            solver.set_pins(styles.pinned_vertices(self.weights, settings.pin_group))
        if Live.SETTER in changed:
            for field in schema.SOLVER_SETTERS:
                setattr(solver, field.name, field.read(settings))

    def start_from(self, coords):
        """Continue from ``coords`` ((#V,3)) instead of the current shape: the rest shape and the
        factorization stay (a warm start, see bake.py)."""
        self.solver.set_vertices(coords)

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
        self.target.keep()
        rest_store.capture(*self.target.rest)

    def cancel(self):
        """Put back exactly what was there before the run, as far as it still exists.

        The mesh is restored even when its object was deleted during the run:
        another object may share it, and undo reuses the mesh as it is in memory.
        A freed mesh, or one whose vertex count changed, is left alone (output.py).
        """
        self.target.restore()

    def object_alive(self):
        try:
            return self.obj.data == self.mesh and self.target.alive()
        except ReferenceError:  # the object or mesh was deleted while running
            return False
