"""Kinds of settings: how one field of the schema (schema.py) becomes a Blender
property, a plain value (JSON round-trip, live-change detection), a check with
an artist-readable message, and a panel row (drawn by view/sidebar.py after ``widget``).

A field knows nothing of the others; the generic walks at the bottom
(read_all, write_all, check_all, changes) run over a table of fields.
"""

import enum
import math

import numpy as np
from bpy.props import (
    BoolProperty, CollectionProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty,
    StringProperty,
)

from .. import native
from ..errors import SettingsError


class Live(enum.Enum):
    """What a change during a live run needs before the next solver step."""
    NOTHING = "nothing"             # the running solver does not read it (names, UI state, the next run)
    STYLES = "rebuild styles"       # new gauss_core.Style objects (set_styles); no re-factorization
    REGIONS = "reassign regions"    # new face and vertex weights per style (set_face_weights); no re-factorization
    CURVE = "paint curve"           # REGIONS where the paint curve's steepness changed (paint_curve.steepness_of)
    PINS = "re-factor"              # set_pins(): the only change that re-factors the system
    SETTER = "solver setter"        # solver.<name> = value; also the Solver() keyword of that name


class Panel(enum.Enum):
    """Where a field's row is drawn (the panels of ui.py and bake/bake_ui.py), in schema order."""
    MAIN = "main"       # Gauss Stylization panel, under Stylize / Reset
    METHOD = "method"   # Styles sub-panel, above the slot list
    SPHERE = "sphere"   # Styles sub-panel, under From Object / Auto Orient (shown before any slot exists)
    STYLES = "styles"   # Styles sub-panel, under the slot list
    SLOT = "slot"       # Styles sub-panel, the active slot's settings
    SOLVER = "solver"   # Solver sub-panel
    BAKE = "bake"       # Bake sub-panel (bake_ui.py)


class Where:
    """What a check needs to know: the object, the vertex groups read when the run
    started ({name: weights}), and whose setting it is (for messages)."""

    def __init__(self, obj, known_groups, owner_name=None):
        self.obj, self.known_groups, self.owner_name = obj, known_groups, owner_name

    def inside(self, owner_name):
        return Where(self.obj, self.known_groups, owner_name)

    def named(self, label):
        return "%s: %s" % (self.owner_name, label) if self.owner_name else label


def _always(_owner):
    return True


class Field:
    """One setting.

    name:     the property's identifier (part of the scripting interface: keep it)
    label:    its name in the UI and in error messages
    tooltip:  the property's description
    live:     what a change during a live run needs (Live)
    panel:    where its row is drawn (Panel), or None
    text:     the row's label where the panel says it shorter than ``label``
    relevant: owner -> bool; False where the setting has no effect (row hidden, value not checked)
    shown:    owner -> bool; whether the panel shows the row (default: where it is relevant)
    update:   (owner, context) -> None, called by Blender after the property was changed (kinds
              that take it: Choice, Bool)
    since:    the settings version (settings/versioning.py) whose rules brought today's default; objects
              written under an earlier one read ``before`` where they never set the field, so an old
              file keeps its result (object fields only)
    before:   the default before ``since``
    before_where: owner -> bool; where an old object needs ``before`` (default: everywhere). Read after
              the fields of earlier versions were brought up to date, so it may read them.
    added:    the settings version current when a field without ``since`` was added (None: it was there
              before version 1): a whole dump of the settings that an earlier version wrote lacks it, and
              reads its default, under which the run was the same (versioning.as_saved)
    """

    widget = "prop"  # plain layout.prop row

    def __init__(self, name, label, tooltip="", live=Live.NOTHING, panel=None, text=None, relevant=None,
                 shown=None, update=None, since=None, before=None, before_where=None, added=None):
        if (since is None) != (before is None):
            raise ValueError("%s: since and before go together" % name)
        if since is not None and added is not None:
            raise ValueError("%s: a field with since reads before where it is missing, not its default" % name)
        self.name, self.label, self.tooltip = name, label, tooltip
        self.since, self.before, self.added = since, before, added
        self.before_where = before_where or _always
        self.live, self.panel, self.text = live, panel, text
        self.relevant = relevant or _always
        self.shown = shown or self.relevant
        self.update = update

    def read(self, owner):
        return getattr(owner, self.name)

    def write(self, owner, value):
        setattr(owner, self.name, value)

    def check(self, owner, where):
        """Raise SettingsError if the value cannot go to the solver (most kinds: always fine)."""

    def changes(self, old, new):
        return {self.live} if old != new else set()


class _Number(Field):
    """Where the solver owns the setting (its name is in native.facts().limits), default
    and hard range come from the solver and must not be given here; otherwise they must
    be. soft: the UI slider range, None for the hard one."""

    def __init__(self, name, label, tooltip, default=None, hard=None, soft=None, **options):
        super().__init__(name, label, tooltip, **options)
        facts = native.facts()
        owned = name in facts.limits
        if owned and (default is not None or hard is not None):
            raise ValueError("%s: the solver owns its default and range (settings.h)" % name)
        if not owned and (default is None or hard is None):
            raise ValueError("%s: a setting the solver does not own needs a default and a range" % name)
        self.default = self.cast(facts.defaults[name] if owned else default)
        self.hard = tuple(self.cast(x) for x in (facts.limits[name] if owned else hard))
        self.soft = soft or self.hard

    def check(self, owner, where):
        value = getattr(owner, self.name)
        low, high = self.hard
        if not (math.isfinite(value) and low <= value <= high):
            raise SettingsError("%s must be %s between %g and %g (it is %s)"
                                % (where.named(self.label), self.noun, low, high, value))


def _float32_inside(low, high):
    """The float32 range Blender stores as min/max, rounded inwards, so a clamped value passes the check."""
    low32, high32 = np.float32(low), np.float32(high)
    # Compared as Python floats: numpy 2 compares a float32 with a Python float in float32 (NEP 50).
    if float(low32) < low:
        low32 = np.nextafter(low32, np.float32(np.inf))
    if float(high32) > high:
        high32 = np.nextafter(high32, np.float32(-np.inf))
    return float(low32), float(high32)


def shown_decimals(*values):
    """Decimals a number field needs so each of ``values`` shows a significant digit (Blender's
    default, 2, shows 0.001 as "0.00"); at least 2, at most 6 (Blender's limit)."""
    small = [abs(v) for v in values if 0.0 < abs(v) < 1.0]
    return min(6, max([2] + [int(math.ceil(-math.log10(v) - 1e-9)) for v in small]))


class Float(_Number):
    cast, noun = float, "a number"

    def prop(self, _classes):
        low, high = _float32_inside(*self.hard)
        return FloatProperty(name=self.label, description=self.tooltip, default=self.default,
                             min=low, max=high, soft_min=max(self.soft[0], low), soft_max=min(self.soft[1], high),
                             precision=shown_decimals(self.default, self.soft[0]))


class Int(_Number):
    cast, noun = int, "an integer"

    def prop(self, _classes, label=None, tooltip=None):
        """label, tooltip: for another property of the same range (an operator's)."""
        return IntProperty(name=label or self.label, description=tooltip or self.tooltip, default=self.default,
                           min=self.hard[0], max=self.hard[1], soft_min=self.soft[0], soft_max=self.soft[1])


class Bool(Field):
    """A checkbox. Where the solver owns the setting (its name is in native.facts().defaults), the
    default comes from the solver and must not be given here; otherwise it must be.

    new_objects (solver-owned only, with ``since``): the value new objects start with where it is not
    the solver's default; objects written before ``since`` keep the solver's default (``before``)."""
    widget = "checkbox"  # its label beside it across the row, not in the split's narrow left column

    def __init__(self, name, label, tooltip, default=None, new_objects=None, since=None, **options):
        facts = native.facts()
        owned = name in facts.defaults
        if owned == (default is not None):
            raise ValueError("%s: %s" % (name, "the solver owns its default (settings.h)" if owned
                                         else "a setting the solver does not own needs a default"))
        if new_objects is not None and not (owned and since is not None):
            raise ValueError("%s: new_objects is for a setting the solver owns, with since" % name)
        solver_default = bool(facts.defaults[name]) if owned else None
        if new_objects is not None:
            options["before"] = solver_default
        super().__init__(name, label, tooltip, since=since, **options)
        self.default = bool(default if not owned else solver_default if new_objects is None else new_objects)

    def prop(self, _classes):
        options = {"update": self.update} if self.update else {}
        return BoolProperty(name=self.label, description=self.tooltip, default=self.default, **options)


class Choice(Field):
    """An enum. items: (identifier, label, tooltip, number); the numbers are what .blend files store."""

    def __init__(self, name, label, tooltip, items, default, **options):
        super().__init__(name, label, tooltip, **options)
        self.items, self.default = tuple(items), default
        self.identifiers = {item[0] for item in self.items}

    def prop(self, _classes):
        options = {"update": self.update} if self.update else {}
        return EnumProperty(name=self.label, description=self.tooltip, items=self.items, default=self.default,
                            **options)

    def check(self, owner, where):
        # A number saved by a newer version reads back as "" (no item has it).
        if getattr(owner, self.name) not in self.identifiers:
            raise SettingsError("%s holds a value this version does not know; pick another one"
                                % where.named(self.label))


class Text(Field):
    def __init__(self, name, label, tooltip="", default="", **options):
        super().__init__(name, label, tooltip, **options)
        self.default = default

    def prop(self, _classes):
        return StringProperty(name=self.label, description=self.tooltip, default=self.default)


class FilePath(Text):
    """A file's path (the panel offers the file browser); empty: the caller's default."""

    def prop(self, _classes):
        return StringProperty(name=self.label, description=self.tooltip, default=self.default, subtype='FILE_PATH')


class VertexGroup(Text):
    """The name of a vertex group of the object (empty: none)."""
    widget = "vertex_group"

    def check(self, owner, where):
        group = getattr(owner, self.name)
        if not group:
            return
        # A slot has one group, so its name says enough; object-level groups say which setting.
        what = where.owner_name or self.label
        present, known = group in where.obj.vertex_groups, group in where.known_groups
        if present and known:
            return
        if known:  # weights are read once, when stylization starts: deleted during a run
            raise SettingsError("%s: vertex group '%s' was deleted while Stylize was running; "
                                "pick another group (or none) to go on" % (what, group))
        if present:
            raise SettingsError("%s: vertex group '%s' was added after Stylize started; "
                                "restart Stylize to use it" % (what, group))
        raise SettingsError("%s: there is no vertex group '%s' on '%s'" % (what, group, where.obj.name))


class Euler(Field):
    def prop(self, _classes):
        return FloatVectorProperty(name=self.label, description=self.tooltip, size=3,
                                   subtype='EULER', unit='ROTATION')

    def read(self, owner):
        return list(getattr(owner, self.name))

    def check(self, owner, where):
        if not all(math.isfinite(a) for a in getattr(owner, self.name)):
            raise SettingsError(where.named(self.label) + " must be finite angles")


class Direction(Field):
    def __init__(self, name, label, tooltip, default, **options):
        super().__init__(name, label, tooltip, **options)
        self.default = default

    def prop(self, _classes):
        return FloatVectorProperty(name=self.label, description=self.tooltip, size=3, subtype='XYZ',
                                   default=self.default)

    def read(self, owner):
        return list(getattr(owner, self.name))


def normal_problem(values):
    """Why 3 numbers cannot be a preferred normal (None if they can)."""
    if not all(math.isfinite(x) for x in values):
        return "is not a finite vector"
    if sum(x * x for x in values) < 1e-12:
        return "has zero length"
    return None


class Normals(Field):
    """The slot's custom normals: a collection of ``item_class`` read and written
    as a list of 3-vectors through the slot's custom_normal_list / set_custom_normals."""
    widget = "normals"

    def __init__(self, name, label, item_class, **options):
        super().__init__(name, label, **options)
        self.item_class = item_class

    def prop(self, classes):
        return CollectionProperty(type=classes[self.item_class], name=self.label)

    def read(self, owner):
        return [list(normal) for normal in owner.custom_normal_list()]

    def write(self, owner, value):
        owner.set_custom_normals(value)

    def check(self, owner, where):
        normals = owner.custom_normal_list()
        if not normals:
            raise SettingsError(where.owner_name + " is set to Custom but has no normals; add at least one")
        for number, normal in enumerate(normals, 1):
            problem = normal_problem(normal)
            if problem:
                raise SettingsError("%s: custom normal %d %s" % (where.owner_name, number, problem))


class GaussMap(Field):
    """An example's Gauss map: a collection of ``item_class`` (vector, share), read and written as
    rows [x, y, z, share] through the slot's gauss_map_array / set_gauss_map. Its row says how many
    directions it holds; the operator From Gauss Map sets it."""
    widget = "gauss_map"

    def __init__(self, name, label, item_class, **options):
        super().__init__(name, label, **options)
        self.item_class = item_class

    def prop(self, classes):
        return CollectionProperty(type=classes[self.item_class], name=self.label)

    def read(self, owner):
        return owner.gauss_map_array().tolist()

    def write(self, owner, value):
        owner.set_gauss_map(value)

    def check(self, owner, where):
        rows = owner.gauss_map_array()
        if not len(rows):
            raise SettingsError(where.owner_name + " is set to Gauss Map but has no example; use From Gauss Map")
        if not (math.isfinite(float(rows.sum())) and (rows[:, 3] >= 0).all() and rows[:, 3].sum() > 0):
            raise SettingsError(where.owner_name + ": its Gauss map has a bad direction or share; take it again "
                                "with From Gauss Map")


class Index(Field):
    """The active row of a UI list."""

    def prop(self, _classes):
        return IntProperty(name=self.label, default=0)


class Slots(Field):
    """A collection of items described by ``item_fields`` (the style slots)."""

    def __init__(self, name, label, item_class, item_fields, owner_name, **options):
        super().__init__(name, label, **options)
        self.item_class, self.item_fields = item_class, tuple(item_fields)
        self.owner_name = owner_name  # item -> how messages call it
        self.item_effects = {field.live for field in self.item_fields}

    def prop(self, classes):
        return CollectionProperty(type=classes[self.item_class], name=self.label)

    def read(self, owner):
        return [read_all(self.item_fields, item) for item in getattr(owner, self.name)]

    def write(self, owner, value):
        collection = getattr(owner, self.name)
        collection.clear()
        for data in value:
            write_all(self.item_fields, collection.add(), data)

    def check(self, owner, where):
        for item in getattr(owner, self.name):
            check_all(self.item_fields, item, where.inside(self.owner_name(item)))

    def changes(self, old, new):
        if len(old) != len(new):  # items added or removed: everything they carry changed
            return set(self.item_effects)
        found = set()
        for old_item, new_item in zip(old, new):
            found |= changes(self.item_fields, old_item, new_item)
        return found


# -- walks over a table of fields ---------------------------------------------------

def read_all(fields, owner):
    """{name: plain value} of every field (lists, not tuples: the JSON form)."""
    return {field.name: field.read(owner) for field in fields}


def write_all(fields, owner, data, complete=False):
    """Set the fields named in ``data`` (the rest keep their values), in table order.

    Unknown names raise KeyError; with ``complete`` every field must be given."""
    known = {field.name for field in fields}
    unknown = set(data) - known
    if unknown:
        raise KeyError("unknown setting(s) %s; known: %s" % (", ".join(sorted(unknown)), ", ".join(sorted(known))))
    missing = known - set(data)
    if complete and missing:
        raise KeyError("missing setting(s) %s" % ", ".join(sorted(missing)))
    for field in fields:
        if field.name in data:
            field.write(owner, data[field.name])


def check_all(fields, owner, where):
    for field in fields:
        if field.relevant(owner):
            field.check(owner, where)


def changes(fields, old, new):
    """The Live effects of the differences between two read_all() results."""
    found = set()
    for field in fields:
        found |= field.changes(old[field.name], new[field.name])
    found.discard(Live.NOTHING)
    return found
