"""Settings saved by an earlier version keep their meaning when a default changes.

A .blend stores only the settings that were set; one left at its default reads back as today's
default. So when a default changes, each object's settings carry the version of the rules they were
written under (``settings_version``, hidden), and a file that loads brings its objects up to date,
as Blender's own versioning does: the old default is written out where it was in effect, and the
enum numbers files hold never change.

The rules are the schema's (schema.OBJECT): a field whose default changed names the version that
changed it (``since``) and the default before (``before``; fields.Field). Version 0 is before the stamp;
VERSION is the latest ``since``. Objects written under an earlier version that never set such a field
get its ``before`` value written out, so they keep their result; a field that keeps an old rule of
another setting (weigh_finer_faces, Resolution Independent's rule before version 3) gets it only where
that setting is in effect (``before_where``). Recipes of kept runs hold the settings they ran with;
a field they predate is read as ``before`` (as_recorded).

A file's objects are brought up to date when it loads (load_post); objects that got settings in this
session are stamped when the file is saved (save_pre), since they already follow today's rules. An
object stamped with an earlier version that did not come in through load_post (appended from such a
file, or loaded before the add-on was updated in the same session) is brought up to date as soon as
the add-on meets it: when the add-on registers (on a timer, which Blender runs only with a window),
when a run of it is planned or replayed, and at the latest when the file is saved, before the stamp.
Objects without a stamp cannot be told from new ones and follow today's rules (set such a field by
hand to get the old result): one appended from a file saved before the stamp, one in a file opened
while the add-on was off, and one given settings in this session before the add-on was updated.
"""

from types import SimpleNamespace

import bpy
from bpy.props import IntProperty

from .. import app_handlers
from . import schema

# Object fields whose default changed, oldest first.
CHANGED = tuple(sorted((field for field in schema.OBJECT if field.since is not None), key=lambda f: f.since))
VERSION = max(field.since for field in CHANGED)
# Object fields an earlier version's whole dump of the settings may lack (as_saved).
MAY_BE_MISSING = frozenset(field.name for field in schema.OBJECT if field.added is not None or field.since is not None)
STAMP = "settings_version"


def stamp_property():
    """The property GaussSettings carries the stamp in (settings/properties.py)."""
    return IntProperty(name="Settings Version", default=0, min=0, options={'HIDDEN'},
                       description="Version of the add-on's rules these settings were written under")


def _has_settings(obj):
    """Settings a file holds and the add-on may write: a local object's (one without a slot gets one
    when stylized, with the settings it holds). Asked without reading obj.gauss_stylization where it
    was never set, since reading it would give every object of the file settings."""
    return obj.library is None and obj.is_property_set("gauss_stylization")


def _settings_in_file():
    """The settings of every object that has them (_has_settings)."""
    return [obj.gauss_stylization for obj in bpy.data.objects if _has_settings(obj)]


def bring_up_to_date(settings):
    """Settings read from a file of an earlier version -> today's, keeping what they did."""
    if settings.settings_version >= VERSION:
        return
    for field in CHANGED:  # oldest first: a field's before_where reads the older fields brought up to date
        if (settings.settings_version < field.since and not settings.is_property_set(field.name)
                and field.before_where(settings)):
            setattr(settings, field.name, field.before)
    settings.settings_version = VERSION


def bring_stamped_up_to_date(settings):
    """bring_up_to_date where the stamp says an earlier version wrote the settings (0 < stamp < VERSION):
    a stamp of 0 is also what settings made in this session have, which follow today's rules."""
    if 0 < settings.settings_version < VERSION:
        bring_up_to_date(settings)


def _bring_stamped_objects_up_to_date():
    for settings in _settings_in_file():
        bring_stamped_up_to_date(settings)


def as_recorded(data):
    """A kept run's settings as its recipe holds them (settings_io.to_dict when the run started), read
    under the rules they were recorded with: a field whose default changed later is missing from a
    recipe recorded before it existed, and gets its value from before the change (not the object's
    value now), so that Replay and Follow Edits repeat the run bit for bit."""
    return dict({field.name: field.before for field in CHANGED if field.name not in data}, **data)


def as_saved(data):
    """Settings a user saved (a batch preset, a script's settings_json) read as they were saved: a whole
    dump of an object's settings (settings_io.to_dict) that lacks only fields added since (``added``) or
    whose default changed since (``since``) was written by an earlier version. Its missing fields are
    filled, so that it runs as it did then: an added field with its default, a changed one with its
    ``before`` where that version's rules gave it (``before_where``, read on the dump; today's default
    elsewhere). Anything else is a partial set, returned as it is (its missing fields keep the object's
    values)."""
    missing = {field.name for field in schema.OBJECT} - set(data)
    if not missing or not missing <= MAY_BE_MISSING:
        return data
    filled = dict(data)
    for field in schema.OBJECT:
        if field.name in missing and field.added is not None:
            filled[field.name] = field.default
    for field in CHANGED:  # oldest first: a field's before_where reads the older fields filled in
        if field.name in missing:
            filled[field.name] = field.before if field.before_where(SimpleNamespace(**filled)) else field.default
    return filled


@bpy.app.handlers.persistent
def _update_loaded_file(*_args):
    for settings in _settings_in_file():
        bring_up_to_date(settings)


@bpy.app.handlers.persistent
def _stamp_before_save(*_args):
    for settings in _settings_in_file():
        bring_stamped_up_to_date(settings)  # an older version's: brought up to date
        settings.settings_version = VERSION  # this session's: stamped (already today's)


HANDLERS = (("load_post", _update_loaded_file), ("save_pre", _stamp_before_save))

_pending = []  # the timer register_handlers() started, until it has run


def register_handlers():
    app_handlers.add(HANDLERS)
    # A file open while the add-on is enabled or updated was read by an older add-on, or by none: its
    # stamped objects are brought up to date once Blender lets the add-on write (not inside register).
    # A new function each time: registered again as one function (if not is_registered), the bring-up
    # after an update right after enabling was missed one time in three in a window, this way never.
    def bring_up_to_date_once():
        if bring_up_to_date_once in _pending:
            _pending.remove(bring_up_to_date_once)
        _bring_stamped_objects_up_to_date()
        return None
    _cancel_pending()
    _pending.append(bring_up_to_date_once)
    bpy.app.timers.register(bring_up_to_date_once, first_interval=0.0)


def _cancel_pending():
    while _pending:
        timer = _pending.pop()
        if bpy.app.timers.is_registered(timer):
            bpy.app.timers.unregister(timer)


def unregister_handlers():
    app_handlers.remove(HANDLERS)
    _cancel_pending()
