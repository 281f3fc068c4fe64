"""Square Flat Regions through gauss_core: Solver(square_flat_regions=...) squares the cap of a capped
32-sided cylinder with either method, can be switched during a run, and off changes nothing, bit for bit.
The figures: docs/styles.md#square-flat-regions."""
import numpy as np
import pytest

import gauss_core
from flat_meshes import capped_cylinder, pot
from measures import squareness

V, F = capped_cylinder()
CASES = [dict(method="cubic", cubic_lambda=0.2), dict(method="cubic", cubic_lambda=0.4), dict(lam=1.0)]


def _run(V, F, steps=None, **keywords):
    s = gauss_core.Solver(V, F, **keywords)
    if steps is None:
        s.step_until(gauss_core.DEFAULTS["tolerance"], 300)
    else:
        s.step(steps)
    out = s.vertices
    assert np.isfinite(out).all()
    return out


def test_it_is_an_option_off_by_default():
    assert gauss_core.DEFAULTS["square_flat_regions"] is False
    s = gauss_core.Solver(V, F)
    assert s.square_flat_regions is False
    s.square_flat_regions = True
    assert s.square_flat_regions is True


def test_a_round_cap_and_a_pots_lid_turn_square():
    assert squareness(V, F) == pytest.approx(0.78, abs=0.01)  # the 32-gon: about a circle's pi/4
    P, G = pot()
    for case in CASES:
        assert squareness(_run(V, F, **case), F) < 0.9, case
        assert squareness(_run(V, F, square_flat_regions=True, **case), F) >= 0.9, case
    assert squareness(_run(P, G, square_flat_regions=True, method="cubic", cubic_lambda=0.2), G) >= 0.9


def test_off_is_bit_for_bit_the_run_without_it():
    for case in CASES:
        assert np.array_equal(_run(V, F, steps=10, square_flat_regions=False, **case), _run(V, F, steps=10, **case))


def test_switched_on_during_a_run_it_takes_effect_at_the_next_step():
    plain = gauss_core.Solver(V, F, method="cubic")
    switched = gauss_core.Solver(V, F, method="cubic")
    plain.step(3)
    switched.step(3)
    switched.square_flat_regions = True
    plain.step(20)
    switched.step(20)
    assert squareness(switched.vertices, F) > squareness(plain.vertices, F) + 0.03
