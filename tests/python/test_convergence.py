"""Running until converged through gauss_core: last_reldv, step_until, converged, tolerance."""
import math

import numpy as np
import pytest

import gauss_core
from conftest import SHARED_MESHES
from gil import run_beside_python
from meshes import icosphere, read_obj
from measures import aligned_share


def reldv(previous, current, rest):
    """reldV as fixed_point_iteration.h defines it (the reference cubic code's stopping rule), in the
    caller's frame."""
    return np.abs(current - previous).max() / np.abs(current - rest).max()


def test_last_reldv_is_the_largest_change_over_the_largest_displacement():
    V, F = icosphere(3)
    V = V * 7.0 + [1.0, -2.0, 3.0]  # any frame: reldV is scale- and translation-invariant
    s = gauss_core.Solver(V, F, acceleration=False)  # accelerated: see the test below
    assert s.last_reldv == math.inf and not s.converged
    previous = s.vertices
    for _ in range(25):
        s.step()
        current = s.vertices
        assert s.last_reldv == pytest.approx(reldv(previous, current, V), rel=1e-9)
        previous = current


def test_accelerated_reldv_is_how_far_one_plain_step_moves():
    """With acceleration a step is applied at a momentum point, and reldV is measured from there: a
    converged accelerated result is one that a plain step barely moves (the same verdict as plain)."""
    V, F = icosphere(4)
    s = gauss_core.Solver(V, F)
    assert s.acceleration == gauss_core.DEFAULTS["acceleration"] is True
    s.step_until(1e-3, 1000)
    plain = gauss_core.Solver(V, F, acceleration=False)
    plain.set_vertices(s.vertices)
    plain.step()
    assert plain.last_reldv < 2e-3, plain.last_reldv


def _converge(V, F, method, acceleration):
    """(steps, cube-aligned share) of the cube style (Gauss: lambda 4, sigma 4; the cubic method at its
    default lambda) run until reldV < 1e-3."""
    s = gauss_core.Solver(V, F, lam=4.0, method=method, acceleration=acceleration)
    s.set_styles([gauss_core.Style.preset("cube", sigma=4.0)])
    steps = s.step_until(1e-3, 2000)
    assert s.converged and s.acceleration == acceleration
    return steps, aligned_share(s.vertices, F, gauss_core.Style.preset("cube").normals)


def _expect_same_result_in_fewer_steps(V, F, method, max_step_ratio):
    plain, fast = _converge(V, F, method, False), _converge(V, F, method, True)
    assert fast[0] < max_step_ratio * plain[0], (plain, fast)
    assert abs(fast[1] - plain[1]) < 0.02, (plain, fast)
    # Both runs stylized (two unstylized runs would agree too).
    rest = aligned_share(V, F, gauss_core.Style.preset("cube").normals)
    assert plain[1] > rest + 0.15, (rest, plain)


# Measured (as tests/cpp/test_acceleration.cpp): icosphere(4) Gauss 31 -> 19 steps (shares 0.8962 and 0.8971),
# cubic 62 -> 19 (0.6428 and 0.6427; the cubic method's ADMM state is extrapolated with the vertices).
@pytest.mark.parametrize("method, max_step_ratio", [("gauss", 0.75), ("cubic", 0.5)])
def test_accelerated_and_plain_runs_reach_the_same_result_in_fewer_steps(method, max_step_ratio):
    V, F = icosphere(4)
    _expect_same_result_in_fewer_steps(V, F, method, max_step_ratio)


def test_accelerated_and_plain_runs_reach_the_same_result_in_fewer_steps_on_spot():
    path = SHARED_MESHES / "small" / "spot_triangulated_2930.obj"
    if not path.exists():
        pytest.skip("../shared/meshes not present")
    V, F = read_obj(path)
    # Measured: 181 plain steps, 67 accelerated; area-weighted shares 0.7736 and 0.7745.
    _expect_same_result_in_fewer_steps(V, F, "gauss", 0.5)


def test_step_until_stops_at_the_tolerance_and_respects_the_cap():
    V, F = icosphere(3)
    s = gauss_core.Solver(V, F)
    taken = s.step_until(1e-3, 1000)
    assert 5 < taken < 1000 and s.step_count == taken
    assert s.last_reldv < 1e-3 and s.converged and s.tolerance == 1e-3
    plain = gauss_core.Solver(V, F)
    plain.step(taken - 1)
    assert plain.last_reldv >= 1e-3  # it stopped at the first step below the tolerance
    assert s.step_until(None, 1000) == 0  # None: the solver's tolerance, already met

    capped = gauss_core.Solver(V, F)
    assert capped.step_until(1e-4, 7) == 7
    assert capped.step_count == 7 and not capped.converged


def test_converged_follows_the_tolerance_and_edits():
    V, F = icosphere(2)
    s = gauss_core.Solver(V, F, tolerance=1e-2)
    assert s.tolerance == 1e-2
    s.step_until(None, 1000)
    assert s.converged and s.last_reldv < 1e-2
    s.tolerance = s.last_reldv / 2  # the tolerance only changes the verdict
    assert not s.converged
    s.tolerance = 1e-2
    assert s.converged
    for edit in (lambda: setattr(s, "lam", 5.0), lambda: s.set_styles([gauss_core.Style.preset("octahedron")]),
                 lambda: s.set_pins([0]), lambda: s.set_pin_positions([V[0] + 0.05]), s.reset):
        s.step_until(None, 1000)
        assert s.converged
        edit()
        assert not s.converged and s.last_reldv == math.inf
        assert s.step_until(None, 1000) >= 1


@pytest.mark.parametrize("call, error, message", [
    (lambda s: s.step_until(0.0, 10), ValueError, "tolerance must be"),
    (lambda s: s.step_until(float("nan"), 10), ValueError, "tolerance must be"),
    (lambda s: s.step_until(1e-3, -1), ValueError, "steps must be"),
    (lambda s: s.step_until("small", 10), (TypeError, RuntimeError), ""),
    (lambda s: setattr(s, "tolerance", 5.0), ValueError, "tolerance must be"),
])
def test_bad_arguments_are_refused_without_stepping(call, error, message):
    V, F = icosphere(1)
    s = gauss_core.Solver(V, F)
    with pytest.raises(error, match=message):
        call(s)
    assert s.step_count == 0 and s.tolerance == gauss_core.DEFAULTS["tolerance"]
    with pytest.raises(ValueError, match="tolerance must be"):
        gauss_core.Solver(V, F, tolerance=0.0)


def test_step_until_releases_the_gil():
    V, F = icosphere(5)
    s = gauss_core.Solver(V, F)
    steps, seconds, longest_pause = run_beside_python(lambda: s.step_until(gauss_core.LIMITS["tolerance"][0], 20))
    assert steps == 20 and seconds > 0.02
    assert longest_pause < 0.5 * seconds, (longest_pause, seconds)


def test_set_vertices_is_a_warm_start_that_keeps_rest_shape_and_pins():
    V, F = icosphere(3)
    s = gauss_core.Solver(V, F, pinned=[0], pin_positions=[V[0] + [0.0, 0.0, 0.1]])
    cold = s.step_until(1e-3, 2000)
    result = s.vertices
    warm = gauss_core.Solver(V, F, pinned=[0], pin_positions=[V[0] + [0.0, 0.0, 0.1]])
    moved = result.astype(np.float32)  # Blender's dtype
    moved[0] += 0.5  # a pin: stays at its target whatever is given
    warm.set_vertices(moved)
    np.testing.assert_array_equal(warm.vertices[0], V[0] + [0.0, 0.0, 0.1])
    np.testing.assert_allclose(warm.vertices[1:], moved[1:], atol=1e-6)
    assert warm.last_reldv == math.inf and warm.factorization_count == 1
    assert warm.step_until(1e-3, 2000) < cold / 4
    warm.reset()  # back to the rest shape, not to the warm start
    np.testing.assert_allclose(warm.vertices[1:], V[1:], atol=1e-12)
    assert warm.step_count == 0


@pytest.mark.parametrize("make, error, message", [
    (lambda V: V[:-1], ValueError, "one row per vertex"),
    (lambda V: V[:, :2], ValueError, "shape"),
    (lambda V: np.where(np.arange(len(V))[:, None] == 4, np.nan, V), ValueError, "vertex 4 has a NaN"),
    (lambda V: np.where(np.arange(len(V))[:, None] == 4, 1e30, V), ValueError, "vertex 4 is too far"),
    (lambda V: V.astype(str), TypeError, "floating-point"),
    (lambda V: "vertices", TypeError, ""),
])
def test_set_vertices_refuses_bad_arrays_without_effect(make, error, message):
    V, F = icosphere(2)
    s = gauss_core.Solver(V, F)
    s.step(3)
    before = s.vertices
    with pytest.raises(error, match=message):
        s.set_vertices(make(V))
    np.testing.assert_array_equal(s.vertices, before)
