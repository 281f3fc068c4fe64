"""Moving pins without re-factoring: Solver.set_pin_positions, Solver.pinned and
Solver.pin_positions, as the add-on's handle dragging uses them."""
import numpy as np
import pytest

import gauss_core
from meshes import icosphere

V, F = icosphere(3)
BOTTOM = np.flatnonzero(V[:, 2] < -0.8)
TOP = np.flatnonzero(V[:, 2] > 0.9)
PINS = np.concatenate([BOTTOM, TOP])
MOVED = V[PINS] + np.where(np.isin(PINS, TOP)[:, None], [0.3, 0.0, 0.0], 0.0)  # drag the top along x


def pinned_solver(targets=None):
    return gauss_core.Solver(V, F, pinned=PINS, pin_positions=V[PINS] if targets is None else targets)


def test_moving_pins_does_not_refactor_and_equals_a_solver_built_with_the_targets():
    dragged, built = pinned_solver(), pinned_solver(MOVED)
    dragged.set_pin_positions(MOVED)
    dragged.step(20)
    built.step(20)
    assert dragged.factorization_count == 1
    np.testing.assert_array_equal(dragged.vertices, built.vertices)


def test_during_a_run_the_pins_sit_at_their_new_targets_and_the_mesh_follows():
    s = pinned_solver()
    s.step(10)
    before = s.vertices
    for k in range(1, 4):  # a drag: several small moves, one step each
        s.set_pin_positions(V[PINS] + (MOVED - V[PINS]) * k / 3)
        s.step()
        np.testing.assert_array_equal(s.vertices[PINS], V[PINS] + (MOVED - V[PINS]) * k / 3)
    band = np.flatnonzero((V[:, 2] > 0.5) & (V[:, 2] <= 0.9))
    assert (s.vertices[band, 0] - before[band, 0]).mean() > 0.03  # measured 0.06 (the top moved 0.3)
    assert s.factorization_count == 1


def test_pinned_and_pin_positions_read_back():
    s = pinned_solver()
    assert s.pinned.dtype == np.int64 and s.pinned.shape == (len(PINS),)
    np.testing.assert_array_equal(s.pinned, PINS)
    np.testing.assert_array_equal(s.pin_positions, V[PINS])
    s.set_pin_positions(MOVED.astype(np.float32))  # Blender's dtype
    np.testing.assert_array_equal(s.pin_positions, MOVED.astype(np.float32))
    s.pinned[0] = 7  # copies: the solver is not changed through them
    s.pin_positions[0] = 7.0
    np.testing.assert_array_equal(s.pinned, PINS)
    s.set_pins([4, 2])
    np.testing.assert_array_equal(s.pinned, [4, 2])
    np.testing.assert_array_equal(s.pin_positions, V[[4, 2]])
    free = gauss_core.Solver(V, F)
    assert free.pinned.shape == (0,) and free.pin_positions.shape == (0, 3)
    free.set_pin_positions(np.zeros((0, 3)))  # nothing to move
    assert free.factorization_count == 1


@pytest.mark.parametrize("positions, exc, words", [
    (MOVED[:-1], ValueError, "one row per pinned vertex"),
    (np.vstack([MOVED, MOVED[:1]]), ValueError, "one row per pinned vertex"),
    (MOVED[:, :2], ValueError, "shape (n, 3)"),
    (MOVED.ravel(), ValueError, "shape (n, 3)"),
    (np.where(np.arange(len(PINS))[:, None] == 2, np.nan, MOVED), ValueError, "NaN"),
    (np.where(np.arange(len(PINS))[:, None] == 2, np.inf, MOVED), ValueError, "NaN or infinite"),
    (MOVED + [1e13, 0, 0], ValueError, "too far"),
    (MOVED.astype(str), TypeError, "floating-point dtype"),
    (None, TypeError, "positions"),
])
def test_bad_targets_are_refused_and_change_nothing(positions, exc, words):
    reference, s = pinned_solver(), pinned_solver()
    with pytest.raises(exc) as info:
        s.set_pin_positions(positions)
    assert words in str(info.value)
    reference.step(5)
    s.step(5)
    np.testing.assert_array_equal(s.vertices, reference.vertices)
    np.testing.assert_array_equal(s.pin_positions, reference.pin_positions)
    assert s.factorization_count == 1
