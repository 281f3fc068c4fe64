"""Settings saved in the .blend: ``Object.gauss_stylization``.

The PropertyGroups are built from the tables of schema.py (one property per
field); this file only adds the methods scripts use on a slot. Everything is
a plain RNA property (no pickled or evaluated strings), so saving, reopening
and scripting work with the usual Blender tools.
"""

import bpy
import numpy as np
from bpy.props import PointerProperty

from . import schema, versioning
from .fields import normal_problem


def _properties(table, **item_classes):
    """The annotations of a PropertyGroup: one property per field; collections find
    their item class by name in ``item_classes``."""
    return {field.name: field.prop(item_classes) for field in table}


class GaussNormal(bpy.types.PropertyGroup):
    __annotations__ = _properties(schema.NORMAL)


def _checked_normal(vector):
    """One user-given normal as a tuple of 3 finite floats with non-zero length."""
    try:
        values = tuple(float(x) for x in vector)
    except (TypeError, ValueError):
        raise TypeError("a custom normal must be 3 numbers, got %r" % (vector,)) from None
    if len(values) != 3:
        raise ValueError("a custom normal must have 3 components, got %d" % len(values))
    problem = normal_problem(values)
    if problem:
        raise ValueError("a custom normal %s: %r" % (problem, values))
    return values


class GaussMapCell(bpy.types.PropertyGroup):
    __annotations__ = _properties(schema.GAUSS_MAP_CELL)


class GaussStyleSlot(bpy.types.PropertyGroup):
    __annotations__ = _properties(schema.SLOT, GaussNormal=GaussNormal, GaussMapCell=GaussMapCell)

    def set_gauss_map(self, rows):
        """Replace the example's Gauss map with ``rows`` (M by 4: direction x, y, z and area share).

        Validates everything before touching the slot, so a bad array leaves it as it was."""
        rows = np.asarray(rows, np.float64).reshape(-1, 4) if len(rows) else np.zeros((0, 4))
        if not np.isfinite(rows).all() or (rows[:, 3] < 0).any() or (len(rows) and not rows[:, 3].sum() > 0):
            raise ValueError("a Gauss map needs finite directions and shares >= 0 with a positive sum")
        if (np.linalg.norm(rows[:, :3], axis=1) < 1e-6).any():
            raise ValueError("a Gauss map's directions must not be zero")
        self.gauss_map.clear()
        for _ in range(len(rows)):
            self.gauss_map.add()
        self.gauss_map.foreach_set("vector", rows[:, :3].astype(np.float32).ravel())
        self.gauss_map.foreach_set("share", rows[:, 3].astype(np.float32))

    def gauss_map_array(self):
        """The example's Gauss map: M by 4 float64 rows (direction x, y, z and area share)."""
        count = len(self.gauss_map)
        vectors = np.empty(3 * count, np.float32)
        shares = np.empty(count, np.float32)
        self.gauss_map.foreach_get("vector", vectors)
        self.gauss_map.foreach_get("share", shares)
        return np.column_stack([vectors.reshape(-1, 3), shares]).astype(np.float64)

    def set_custom_normals(self, vectors):
        """Replace the custom normals with ``vectors`` (a list of 3-vectors).

        Validates everything before touching the slot, so a bad list leaves it as it was.
        """
        checked = [_checked_normal(v) for v in vectors]
        self.custom_normals.clear()
        for values in checked:
            self.custom_normals.add().vector = values
        self.active_normal_index = 0

    def custom_normal_list(self):
        return [tuple(item.vector) for item in self.custom_normals]


class GaussSettings(bpy.types.PropertyGroup):
    __annotations__ = {**_properties(schema.OBJECT, GaussStyleSlot=GaussStyleSlot),
                       versioning.STAMP: versioning.stamp_property()}


classes = (GaussNormal, GaussMapCell, GaussStyleSlot, GaussSettings)


def register_pointer():
    bpy.types.Object.gauss_stylization = PointerProperty(type=GaussSettings)


def unregister_pointer():
    del bpy.types.Object.gauss_stylization
