"""Every setting settings.h declares reaches Python through its bindings table: as a keyword of
gauss_core.Solver (or of gauss_core.Style for a style's settings), as a property of the same name that
reads back what the keyword set and documents where its default is, and in DEFAULTS. The header is read
itself (settings_header.py), so a setting added there without a row in settings::solver_settings fails
here."""
import re

import pytest

import gauss_core
import settings_header
from meshes import icosphere

V, F = icosphere(1)
FIXED = ("V", "F", "pinned", "pin_positions", "progress")  # Solver's arguments that are not settings


def keywords(function):
    """The parameter names of a pybind11 function, from the signature line of its doc."""
    signature = function.__doc__.splitlines()[0]
    return re.findall(r"(\w+): ", signature.split("(", 1)[1])


SOLVER_KEYWORDS = [k for k in keywords(gauss_core.Solver.__init__) if k not in FIXED and k != "self"]
STYLE_KEYWORDS = set(keywords(gauss_core.Style.preset))
DECLARED = settings_header.declared()


def other_value(name):
    """A valid value of the setting other than its default."""
    default = gauss_core.DEFAULTS[name]
    if isinstance(default, bool):
        return not default
    if isinstance(default, str):
        return next(m for m in gauss_core.METHODS if m != default)
    lo, hi = gauss_core.LIMITS[name]
    return type(default)(hi if default != hi else lo)


def test_the_header_is_read():
    assert {"lam", "tolerance", "keep_volume", "acceleration", "avoid_self_intersections", "method"} <= set(DECLARED)


@pytest.mark.parametrize("name", sorted(DECLARED))
def test_every_declared_setting_is_a_keyword_a_property_and_a_default(name):
    assert name in gauss_core.DEFAULTS
    if name in STYLE_KEYWORDS:  # a style's setting: gauss_core.Style takes and shows it
        assert getattr(gauss_core.Style.preset("cube"), name) == gauss_core.DEFAULTS[name]
        return
    assert name in SOLVER_KEYWORDS, "%s is in settings.h but not a keyword of gauss_core.Solver" % name
    prop = gauss_core.Solver.__dict__[name]
    assert isinstance(prop, property) and prop.fset is not None, name
    assert "DEFAULTS['%s']" % name in prop.__doc__, prop.__doc__


def test_every_solver_keyword_is_a_declared_setting():
    assert set(SOLVER_KEYWORDS) <= set(DECLARED)
    assert set(SOLVER_KEYWORDS) | STYLE_KEYWORDS >= set(gauss_core.DEFAULTS) - {"preset"}


def test_settings_are_keyword_only():
    # Bound by name from the table: no position of Solver() after pin_positions takes a setting, so no
    # two settings (the adjacent bools) can be swapped by order.
    with pytest.raises(TypeError):
        gauss_core.Solver(V, F, None, None, gauss_core.DEFAULTS["lam"])
    with pytest.raises(TypeError):
        gauss_core.Solver(V, F, None, None, True)


@pytest.mark.parametrize("name", SOLVER_KEYWORDS)
def test_a_keyword_sets_its_own_property_and_no_other(name):
    value = other_value(name)
    by_keyword = gauss_core.Solver(V, F, **{name: value})
    by_property = gauss_core.Solver(V, F)
    setattr(by_property, name, value)
    for s in (by_keyword, by_property):
        for other in SOLVER_KEYWORDS:
            expected = value if other == name else gauss_core.DEFAULTS[other]
            assert getattr(s, other) == expected and type(getattr(s, other)) is type(expected), (name, other)


def test_a_bad_keyword_is_refused_before_the_set_up():
    p = gauss_core.Progress()
    with pytest.raises(ValueError, match="method must be one of"):
        gauss_core.Solver(V, F, method="cubicle", progress=p)
    with pytest.raises(ValueError, match="tolerance must be"):
        gauss_core.Solver(V, F, tolerance=0.0, progress=p)
    assert p.phase == "", "the set-up began before the settings were checked"
