"""Settings saved in the .blend: ``Object.gauss_stylization``.

Everything the solver needs is stored here as plain RNA properties (no
pickled or evaluated strings), so saving, reopening and scripting work with
the usual Blender tools.
"""

import math

import bpy
from bpy.props import (
    CollectionProperty, EnumProperty, FloatProperty,
    FloatVectorProperty, IntProperty, PointerProperty, StringProperty,
)

from . import native

CUSTOM = 'CUSTOM'


def preset_identifier(name):
    """Solver preset name -> enum identifier ('square_pyramid' -> 'SQUARE_PYRAMID')."""
    return name.upper()


def _preset_items():
    # Enum values are saved in .blend files as numbers, so every known preset
    # keeps a fixed number; presets a newer solver adds get numbers from 200 on.
    known = {name: i for i, name in enumerate(native.FALLBACK_PRESETS)}
    items = []
    extra = 200
    for name in native.available_presets():
        number = known.get(name)
        if number is None:
            number, extra = extra, extra + 1
        label = name.replace("_", " ").title()
        items.append((preset_identifier(name), label,
                      "Prefer the face normals of a %s" % label.lower(), number))
    items.append((CUSTOM, "Custom", "Prefer the normals listed below", 99))
    return items


PRESET_ITEMS = _preset_items()


class GaussNormal(bpy.types.PropertyGroup):
    vector: FloatVectorProperty(
        name="Normal", size=3, subtype='XYZ', default=(0.0, 0.0, 1.0),
        description="Preferred face normal (object space, need not be unit length)")


def _checked_normal(vector):
    """One user-given normal as a tuple of 3 finite floats with non-zero length."""
    try:
        values = tuple(float(x) for x in vector)
    except (TypeError, ValueError):
        raise TypeError("a custom normal must be 3 numbers, got %r" % (vector,)) from None
    if len(values) != 3:
        raise ValueError("a custom normal must have 3 components, got %d" % len(values))
    if not all(math.isfinite(x) for x in values):
        raise ValueError("a custom normal must be finite, got %r" % (values,))
    if sum(x * x for x in values) < 1e-12:
        raise ValueError("a custom normal cannot have zero length")
    return values


class GaussStyleSlot(bpy.types.PropertyGroup):
    # 'name' is what the UIList shows and renames (double-click).
    name: StringProperty(name="Name", default="Style")
    preset: EnumProperty(
        name="Style", items=PRESET_ITEMS, default='CUBE',
        description="Shape whose face normals this region prefers, or your own normals")
    sigma: FloatProperty(
        name="Sigma", default=4.0, min=0.0, soft_min=0.1, max=1000.0, soft_max=20.0,
        description="Sharpness: higher values pull normals closer to the preferred ones")
    mu: FloatProperty(
        name="Mu", default=1.0, min=0.0, max=1000.0, soft_max=10.0,
        description="Strength of this style relative to the others")
    orientation: FloatVectorProperty(
        name="Orientation", size=3, subtype='EULER', unit='ROTATION',
        description="Rotation of the preferred normals (object space)")
    axis_contribution: FloatProperty(
        name="Axis Contribution", default=0.5, min=0.0, max=1.0,
        description="Weight of the axis normals for presets that have them")
    vertex_group: StringProperty(
        name="Vertex Group",
        description="Region of this style (faces whose vertex weights average above 0.5); "
                    "empty means the whole mesh")
    custom_normals: CollectionProperty(type=GaussNormal)
    active_normal_index: IntProperty(default=0)

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
    lam: FloatProperty(
        name="Lambda", default=4.0, min=0.0, max=1.0e4, soft_max=20.0,
        description="How strongly faces follow their style versus keeping their shape "
                    "(changing it while running re-prepares the solver)")
    admm_iterations: IntProperty(
        name="ADMM Iterations", default=1, min=1, max=100,
        description="Inner iterations per solver step")
    iterations: IntProperty(
        name="Script Steps", default=100, min=0, max=100000,
        description="Steps run by Stylize when called from a script or in background mode")
    output: EnumProperty(
        name="Output", default='MESH',
        items=(('MESH', "Mesh", "Move the vertices of the mesh itself"),
               ('SHAPE_KEY', "Shape Key",
                "Write the result into the shape key 'Gauss Stylized' to blend it with its slider")))
    pin_group: StringProperty(
        name="Pin Group", description="Vertices in this group (weight above 0.5) keep their position")
    uncovered: EnumProperty(
        name="Uncovered Faces", default='FIRST_SLOT',
        items=(('FIRST_SLOT', "First Style", "Faces outside every style's group use the first style"),
               ('UNSTYLED', "Unstyled", "Faces outside every style's group only keep their shape")))
    styles: CollectionProperty(type=GaussStyleSlot)
    active_style_index: IntProperty(name="Active Style", default=0)


classes = (GaussNormal, GaussStyleSlot, GaussSettings)


def register_pointer():
    bpy.types.Object.gauss_stylization = PointerProperty(type=GaussSettings)


def unregister_pointer():
    del bpy.types.Object.gauss_stylization
