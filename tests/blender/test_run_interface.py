"""What a live run is, written once (run/run_interface.py): the live Stylize and both bake operators
implement it, member for member, with parameters that accept every call the interface allows."""
import inspect

import pytest


def _members(protocol):
    """{name: the protocol's function or property} of a typing.Protocol and its bases."""
    members = {}
    for cls in reversed(protocol.__mro__):
        if cls is object or cls.__module__ == "typing":
            continue
        for name, value in vars(cls).items():
            if not name.startswith("_") and (inspect.isfunction(value) or isinstance(value, property)):
                members[name] = value
    return members


def problems(cls, protocol):
    """How ``cls`` falls short of ``protocol`` (empty: it implements it)."""
    found = []
    for name, wanted in _members(protocol).items():
        have = inspect.getattr_static(cls, name, None)  # statically, so that no property runs
        if have is None and hasattr(cls, "bl_rna") and name in cls.bl_rna.functions:
            continue  # bpy.types.Operator's own (report): an RNA function, not a Python attribute
        if have is None:
            found.append("%s has no %s" % (cls.__name__, name))
        elif isinstance(wanted, property):
            if inspect.isfunction(have):
                found.append("%s.%s is a method, the interface has a property" % (cls.__name__, name))
        elif not callable(have):
            found.append("%s.%s is not a method" % (cls.__name__, name))
        elif inspect.isfunction(have):
            want = list(inspect.signature(wanted).parameters.values())
            got = list(inspect.signature(have).parameters.values())
            extra = got[len(want):]
            if [p.name for p in got[:len(want)]] != [p.name for p in want] or any(
                    p.default is inspect.Parameter.empty and p.kind is not p.VAR_KEYWORD for p in extra):
                found.append("%s.%s%s does not take %s%s" % (cls.__name__, name, inspect.signature(have),
                                                             name, inspect.signature(wanted)))
            for mine, theirs in zip(got, want):
                if theirs.default is not inspect.Parameter.empty and mine.default is inspect.Parameter.empty:
                    found.append("%s.%s: %s needs a default" % (cls.__name__, name, mine.name))
    return found


def test_the_live_stylize_is_a_stylize_run(addon):
    assert problems(addon.operators.OBJECT_OT_gauss_stylize, addon.run.run_interface.StylizeRun) == []


@pytest.mark.parametrize("name", ["OBJECT_OT_gauss_bake_animation", "OBJECT_OT_gauss_bake_progress"])
def test_the_bakes_are_runs(addon, name):
    assert problems(getattr(addon.bake.bake_operators, name), addon.run.run_interface.Run) == []


def test_the_check_finds_what_is_missing_or_called_otherwise(addon):
    interface = addon.run.run_interface

    class Wrong:
        sessions = ()

        def stop(self, context):  # no keep
            pass

        def cancel_keeping_edits(self, context):
            pass

        def hold_for_save(self, context):
            pass

        def report(self, type, message):
            pass

        def panel_state(self):
            pass

    found = problems(Wrong, interface.Run)
    assert any("has no resume_after_save" in p for p in found), found
    assert any("Wrong.stop" in p for p in found), found
    assert len(found) == 2, found
