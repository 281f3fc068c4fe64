"""The settings table, preset registry, methods and size limits as gauss_core exports them (DEFAULTS,
LIMITS, PRESETS, METHODS, SIZE_LIMITS), as the build writes them for the add-on (core_facts.json), and as
the solver enforces them."""
import json
import math

import numpy as np
import pytest

import gauss_core
import settings_header
from conftest import BUILD
from meshes import icosphere

# As settings.h declares them (settings_header.py reads the header): no list of names of its own.
SETTINGS = settings_header.names("Setting")
INTEGER = {name for name in SETTINGS if settings_header.declared()[name][2]}
OPTIONS = settings_header.names("Option")  # on/off: a bool default, no limits
LABEL = {name: settings_header.declared()[name][1] for name in SETTINGS}  # how messages call it
STYLE_SETTINGS = {"sigma", "mu", "axis_contribution"}  # gauss_core.Style's keywords; the rest are Solver's
V, F = icosphere(2)


def test_defaults_and_limits_have_the_documented_keys_and_types():
    assert set(gauss_core.DEFAULTS) == set(SETTINGS) | set(OPTIONS) | {"preset", "method"}
    assert set(gauss_core.LIMITS) == set(SETTINGS)
    for name in SETTINGS:
        lo, hi = gauss_core.LIMITS[name]
        kind = int if name in INTEGER else float
        assert type(gauss_core.DEFAULTS[name]) is kind and type(lo) is kind and type(hi) is kind, name
        assert lo <= gauss_core.DEFAULTS[name] <= hi, name
    assert gauss_core.DEFAULTS["preset"] in gauss_core.PRESETS
    assert gauss_core.DEFAULTS["method"] == "gauss"
    for name in OPTIONS:
        assert type(gauss_core.DEFAULTS[name]) is bool, name


def test_the_method_registry_order_is_unchanged():
    # Saved .blend files store the add-on's method enum by position in this tuple: append only.
    assert gauss_core.METHODS == ("gauss", "cubic")


def test_the_preset_registry_order_is_unchanged():
    # Saved .blend files store the add-on's style enum by position in this tuple: append only.
    assert gauss_core.PRESETS == (
        "cube", "tetrahedron", "octahedron", "dodecahedron", "icosahedron", "square_pyramid",
        "truncated_pyramid", "triangular_prism", "hexagonal_prism", "plane", "cylinder", "cone",
        "double_cone", "sheet_metal")


def test_core_facts_json_written_by_the_build_equals_the_exports():
    facts = json.loads((BUILD / "addon" / "gauss_stylization" / "core_facts.json").read_text())
    assert set(facts) == {"DEFAULTS", "LIMITS", "PRESETS", "METHODS", "SIZE_LIMITS"}
    assert tuple(facts["METHODS"]) == gauss_core.METHODS
    assert facts["SIZE_LIMITS"] == gauss_core.SIZE_LIMITS
    assert facts["DEFAULTS"] == gauss_core.DEFAULTS
    for name, value in facts["DEFAULTS"].items():  # 4.0 stays a float, 1 an int
        assert type(value) is type(gauss_core.DEFAULTS[name]), name
    assert {k: tuple(v) for k, v in facts["LIMITS"].items()} == gauss_core.LIMITS
    assert tuple(facts["PRESETS"]) == gauss_core.PRESETS


def test_a_new_solver_and_keyword_defaults_use_the_defaults():
    s = gauss_core.Solver(V, F)
    assert s.lam == gauss_core.DEFAULTS["lam"]
    assert s.method == gauss_core.DEFAULTS["method"] and s.cubic_lambda == gauss_core.DEFAULTS["cubic_lambda"]
    assert s.admm_iterations == gauss_core.DEFAULTS["admm_iterations"]
    assert s.tolerance == gauss_core.DEFAULTS["tolerance"]
    for name in OPTIONS:
        assert getattr(s, name) is gauss_core.DEFAULTS[name], name
    (style,) = s.styles
    assert style.name == gauss_core.DEFAULTS["preset"]
    for made in (style, gauss_core.Style.preset("cone"), gauss_core.Style([[0, 0, 1]])):
        assert made.sigma == gauss_core.DEFAULTS["sigma"] and made.mu == gauss_core.DEFAULTS["mu"]
        assert made.axis_contribution == gauss_core.DEFAULTS["axis_contribution"]


def _apply(name, value):
    """Uses one setting where the module takes it, steps once, returns the vertices."""
    if name not in STYLE_SETTINGS:
        s = gauss_core.Solver(V, F, method="cubic" if name == "cubic_lambda" else "gauss", **{name: value})
        setattr(s, name, value)
    else:
        s = gauss_core.Solver(V, F)
        s.set_styles([gauss_core.Style.preset("double_cone", **{name: value})])
    s.step()
    return s.vertices


def _just_outside(name):
    lo, hi = gauss_core.LIMITS[name]
    if name in INTEGER:
        return [lo - 1, hi + 1]
    return [np.nextafter(lo, -math.inf), np.nextafter(hi, math.inf), math.nan]


@pytest.mark.parametrize("name", SETTINGS)
def test_every_limit_is_accepted_and_just_outside_is_refused(name):
    for value in gauss_core.LIMITS[name]:
        assert np.isfinite(_apply(name, value)).all(), (name, value)
    for value in _just_outside(name):
        with pytest.raises(ValueError, match=LABEL.get(name, name) + " must be"):
            _apply(name, value)
