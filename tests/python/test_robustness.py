"""Robustness of the gauss_core API: every bad input raises ValueError or TypeError with a
message that says what is wrong, and nothing crashes; odd but valid inputs (lists, non-contiguous or
Fortran-ordered arrays, other dtypes) give the same result as clean ones; broken meshes come out finite
with nothing lost; a refused call leaves the solver as it was.

Imports gauss_core from $GAUSS_BUILD_DIR/python (default: <repo>/build/python).
"""
import os
import pathlib
import sys

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")) / "python"))
import gauss_core  # noqa: E402
from meshes import subdivided_sphere  # noqa: E402


def lumpy_sphere(levels=2):
    """A subdivided octahedron pushed onto a squashed, turned sphere: closed, oriented, not symmetric."""
    V, F = subdivided_sphere([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)],
                             [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)],
                             levels)
    V = V * [1.1, 0.9, 0.7]
    c, s = np.cos(0.4), np.sin(0.4)
    V = V @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]).T @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]]).T
    return np.ascontiguousarray(V), F


V0, F0 = lumpy_sphere()
NV, NF = len(V0), len(F0)


def result(V, F, steps=5, **kw):
    s = gauss_core.Solver(V, F, **kw)
    s.step(steps)
    return s.vertices


# ------------------------------------------------------------------------------------------------
# Bad arrays for the constructor: (id, V, F, keyword arguments, exception, words in the message).

def _bad_constructor_cases():
    big_v = V0.copy()
    big_v[big_v > 0], big_v[big_v <= 0] = 1.7e308, -1.7e308
    nan_v = V0.copy()
    nan_v[4, 1] = np.nan
    inf_v = V0.copy()
    inf_v[4, 2] = -np.inf
    F_hi, F_neg = F0.copy(), F0.copy()
    F_hi[3, 1], F_neg[3, 1] = NV, -1
    return [
        ("V (n,2)", V0[:, :2], F0, {}, ValueError, "V must have shape (n, 3)"),
        ("V 1-d", V0.ravel(), F0, {}, ValueError, "V must have shape (n, 3)"),
        ("V 3-d", V0[:, :, None], F0, {}, ValueError, "V must have shape (n, 3)"),
        ("V 0-d", np.float64(1.0), F0, {}, ValueError, "V must have shape (n, 3)"),
        ("V empty", np.zeros((0, 3)), F0, {}, ValueError, "no vertices"),
        ("V ragged list", [[0, 0, 0], [1, 0]], F0, {}, (TypeError, ValueError), "V"),
        ("V None", None, F0, {}, TypeError, "V must have a floating-point dtype"),
        ("V strings", V0.astype(str), F0, {}, TypeError, "V must have a floating-point dtype"),
        ("V complex", V0.astype(complex), F0, {}, TypeError, "V must have a floating-point dtype"),
        ("V bool", V0 > 0, F0, {}, TypeError, "V must have a floating-point dtype"),
        ("V NaN", nan_v, F0, {}, ValueError, "vertex 4 has a NaN or infinite coordinate"),
        ("V inf", inf_v, F0, {}, ValueError, "vertex 4 has a NaN or infinite coordinate"),
        ("V one point", np.ones_like(V0), F0, {}, ValueError, "extent"),
        ("V extent overflows", big_v, F0, {}, ValueError, "extent"),
        ("F (n,4)", V0, np.hstack([F0, F0[:, :1]]), {}, ValueError, "F must have shape (n, 3)"),
        ("F 1-d", V0, F0.ravel(), {}, ValueError, "F must have shape (n, 3)"),
        ("F 0-d", V0, np.int64(0), {}, ValueError, "F must have shape (n, 3)"),
        ("F empty", V0, np.zeros((0, 3), np.int64), {}, ValueError, "no faces"),
        ("F float", V0, F0.astype(float), {}, TypeError, "F must have an integer dtype"),
        ("F index = #V", V0, F_hi, {}, ValueError, "face 3 refers to vertex"),
        ("F index -1", V0, F_neg, {}, ValueError, "face 3 refers to vertex -1"),
        ("F index 2**40", V0, np.where(F0 == 0, 2 ** 40, F0), {}, ValueError, "refers to vertex"),
        ("F uint64 huge", V0, np.where(F0 == 0, 2 ** 63 + 5, F0).astype(np.uint64), {}, ValueError,
         "refers to vertex"),
        ("F all repeated", V0, np.array([[0, 0, 1], [2, 2, 2]]), {}, ValueError, "no usable triangle"),
        ("pin = #V", V0, F0, {"pinned": [NV]}, ValueError, "out of range"),
        ("pin -1", V0, F0, {"pinned": [-1]}, ValueError, "out of range"),
        ("pin twice", V0, F0, {"pinned": [3, 3]}, ValueError, "more than once"),
        ("pins float", V0, F0, {"pinned": [1.0, 2.0]}, TypeError, "pinned must have an integer dtype"),
        ("pins 2-d", V0, F0, {"pinned": [[1, 2]]}, ValueError, "pinned must have shape"),
        ("pins 0-d", V0, F0, {"pinned": np.int64(3)}, ValueError, "pinned must have shape"),
        ("pin targets count", V0, F0, {"pinned": [1, 2], "pin_positions": V0[:3]}, ValueError,
         "one row per pinned vertex"),
        ("pin targets (n,2)", V0, F0, {"pinned": [1, 2], "pin_positions": V0[:2, :2]}, ValueError,
         "pin_positions must have shape"),
        ("pin targets without pins", V0, F0, {"pin_positions": V0[:2]}, ValueError, "one row per pinned vertex"),
        ("pin target NaN", V0, F0, {"pinned": [1], "pin_positions": [[0, np.nan, 0]]}, ValueError, "NaN"),
        ("pin target 1e300", V0, F0, {"pinned": [1], "pin_positions": [[0, 1e300, 0]]}, ValueError, "too far"),
        ("lambda < 0", V0, F0, {"lam": -1.0}, ValueError, "lambda"),
        ("lambda NaN", V0, F0, {"lam": float("nan")}, ValueError, "lambda"),
        ("lambda inf", V0, F0, {"lam": float("inf")}, ValueError, "lambda"),
        ("lambda 1e300", V0, F0, {"lam": 1e300}, ValueError, "lambda"),
        ("lambda text", V0, F0, {"lam": "4"}, TypeError, ""),
        ("admm 0", V0, F0, {"admm_iterations": 0}, ValueError, "ADMM"),
        ("admm 1001", V0, F0, {"admm_iterations": 1001}, ValueError, "ADMM"),
    ]


@pytest.mark.parametrize("V,F,kw,exc,words", [c[1:] for c in _bad_constructor_cases()],
                         ids=[c[0] for c in _bad_constructor_cases()])
def test_bad_solver_input_is_refused_with_a_message(V, F, kw, exc, words):
    with pytest.raises(exc) as info:
        gauss_core.Solver(V, F, **kw)
    assert words in str(info.value)


# ------------------------------------------------------------------------------------------------
# Bad styles.

ROT90 = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]], float)
BAD_STYLES = [
    ("sigma 0", lambda: gauss_core.Style.preset("cube", sigma=0.0), ValueError, "sigma"),
    ("sigma < 0", lambda: gauss_core.Style([[0, 0, 1]], sigma=-2.0), ValueError, "sigma"),
    ("sigma NaN", lambda: gauss_core.Style.preset("cube", sigma=float("nan")), ValueError, "sigma"),
    ("sigma inf", lambda: gauss_core.Style.preset("cube", sigma=float("inf")), ValueError, "sigma"),
    ("mu < 0", lambda: gauss_core.Style.preset("cube", mu=-0.1), ValueError, "mu"),
    ("mu NaN", lambda: gauss_core.Style([[0, 0, 1]], mu=float("nan")), ValueError, "mu"),
    ("mu 1e200", lambda: gauss_core.Style.preset("cube", mu=1e200), ValueError, "mu"),
    ("no normals, no rings", lambda: gauss_core.Style(), ValueError, "at least one"),
    ("empty normal list", lambda: gauss_core.Style([]), ValueError, "at least one"),
    ("empty normal array", lambda: gauss_core.Style(np.zeros((0, 3))), ValueError, "at least one"),
    ("zero normal", lambda: gauss_core.Style([[0, 0, 0]]), ValueError, "non-zero"),
    ("NaN normal", lambda: gauss_core.Style([[0, np.nan, 1]]), ValueError, "finite"),
    ("normal (2,)", lambda: gauss_core.Style([0, 1]), ValueError, "normals must have shape"),
    ("normals ragged", lambda: gauss_core.Style([[1, 0, 0], [0, 1]]), (TypeError, ValueError), "normals"),
    ("normals text", lambda: gauss_core.Style([["a", "b", "c"]]), TypeError, "normals"),
    ("axis ragged", lambda: gauss_core.Style(axis=[[1, 2], [3]], ring_offsets=[0.5]), (TypeError, ValueError),
     "axis"),
    ("axis (2,)", lambda: gauss_core.Style(axis=[0, 1], ring_offsets=[0.5]), ValueError, "axis"),
    ("axis zero", lambda: gauss_core.Style(axis=[0, 0, 0], ring_offsets=[0.5]), ValueError, "axis"),
    ("ring offset 1", lambda: gauss_core.Style(axis=[0, 0, 1], ring_offsets=[1.0]), ValueError, "ring offsets"),
    ("ring offset NaN", lambda: gauss_core.Style(axis=[0, 0, 1], ring_offsets=[np.nan]), ValueError,
     "ring offsets"),
    ("ring offsets 0-d", lambda: gauss_core.Style(axis=[0, 0, 1], ring_offsets=np.float64(0.5)), ValueError,
     "ring_offsets must have shape"),
    ("rotation scaled", lambda: gauss_core.Style.preset("cube", rotation=2 * np.eye(3)), ValueError, "rotation"),
    ("rotation reflection", lambda: gauss_core.Style.preset("cube", rotation=np.diag([1.0, 1, -1])), ValueError,
     "rotation"),
    ("rotation (2,2)", lambda: gauss_core.Style.preset("cube", rotation=np.eye(2)), ValueError, "rotation"),
    ("rotation ragged", lambda: gauss_core.Style.preset("cube", rotation=[[1, 0], [0, 1, 0], [0, 0, 1]]),
     (TypeError, ValueError), "rotation"),
    ("rotation NaN", lambda: gauss_core.Style.preset("cube", rotation=np.full((3, 3), np.nan)), ValueError,
     "rotation"),
    ("axis contribution < 0", lambda: gauss_core.Style.preset("cone", axis_contribution=-1.0), ValueError,
     "axis_contribution"),
    ("unknown preset", lambda: gauss_core.Style.preset("sphere"), ValueError, "valid presets"),
    ("value at (2,)", lambda: gauss_core.Style.preset("cube").value([1.0, 0.0]), ValueError, "x must have shape"),
    ("value at (n,2)", lambda: gauss_core.Style.preset("cube").gradient(np.ones((4, 2))), ValueError,
     "x must have shape"),
    ("value at ragged", lambda: gauss_core.Style.preset("cube").hessian([[1, 0, 0], [1]]), (TypeError, ValueError),
     "x"),
]


@pytest.mark.parametrize("make,exc,words", [c[1:] for c in BAD_STYLES], ids=[c[0] for c in BAD_STYLES])
def test_bad_style_is_refused_with_a_message(make, exc, words):
    with pytest.raises(exc) as info:
        make()
    assert words in str(info.value)


def test_a_rotated_style_is_accepted():
    np.testing.assert_allclose(gauss_core.Style([[1, 0, 0]], rotation=ROT90).normals, [[0, 1, 0]], atol=1e-15)


# ------------------------------------------------------------------------------------------------
# Bad calls on a working solver; none of them changes what the solver does next.

def _bad_calls():
    cube, cone = gauss_core.Style.preset("cube"), gauss_core.Style.preset("cone")
    return [
        ("no styles for used indices", lambda s: s.set_styles([]), ValueError, "styles were given"),
        ("styles not Style", lambda s: s.set_styles([1, 2]), TypeError, ""),
        ("styles None", lambda s: s.set_styles(None), TypeError, ""),
        ("set_style index 1", lambda s: s.set_style(1, cone), ValueError, "out of range"),
        ("set_style index -1", lambda s: s.set_style(-1, cone), ValueError, "out of range"),
        ("face styles too short", lambda s: s.set_face_styles(np.zeros(NF - 1, np.int64)), ValueError,
         "one entry per face"),
        ("face style 1 of 1", lambda s: s.set_face_styles(np.ones(NF, np.int64)), ValueError, "valid: -1"),
        ("face style -2", lambda s: s.set_face_styles(np.full(NF, -2)), ValueError, "valid: -1"),
        ("face styles float", lambda s: s.set_face_styles(np.zeros(NF)), TypeError, "integer dtype"),
        ("face styles 2-d", lambda s: s.set_face_styles(np.zeros((NF, 2), np.int64)), ValueError, "shape"),
        ("face styles 0-d", lambda s: s.set_face_styles(np.int64(0)), ValueError, "shape"),
        ("face styles ragged", lambda s: s.set_face_styles([[0], [0, 0]]), (TypeError, ValueError), "face_styles"),
        ("face weight NaN", lambda s: s.set_face_weights(np.full((NF, 1), np.nan)), ValueError,
         "weights must be numbers from 0 to 1"),
        ("face weight -0.5", lambda s: s.set_face_weights(np.full((NF, 1), -0.5)), ValueError, "is -0.5"),
        ("face weight 2", lambda s: s.set_face_weights(np.full((NF, 1), 2.0)), ValueError, "from 0 to 1"),
        ("face weights too short", lambda s: s.set_face_weights(np.ones((NF - 1, 1))), ValueError,
         "one row per face"),
        ("face weights for 2 of 1 styles", lambda s: s.set_face_weights(np.ones((NF, 2))), ValueError,
         "at most one column per style"),
        ("face weights 3-d", lambda s: s.set_face_weights(np.ones((NF, 1, 1))), ValueError, "shape"),
        ("face weights text", lambda s: s.set_face_weights(np.full((NF, 1), "a")), TypeError, "floating-point"),
        ("vertex weights too short", lambda s: s.set_face_weights(np.ones((NF, 1)), np.ones((NV - 1, 1))),
         ValueError, "one row per vertex"),
        ("vertex weight NaN", lambda s: s.set_face_weights(np.ones((NF, 1)), np.full((NV, 1), np.nan)),
         ValueError, "the weight of vertex 0"),
        ("pins out of range", lambda s: s.set_pins([0, NV]), ValueError, "out of range"),
        ("pins negative", lambda s: s.set_pins([-3]), ValueError, "out of range"),
        ("pins twice", lambda s: s.set_pins([2, 2]), ValueError, "more than once"),
        ("pin target NaN", lambda s: s.set_pins([2], [[np.nan, 0, 0]]), ValueError, "NaN"),
        ("pin target inf", lambda s: s.set_pins([2], [[np.inf, 0, 0]]), ValueError, "NaN or infinite"),
        ("pin target 1e200", lambda s: s.set_pins([2], [[1e200, 0, 0]]), ValueError, "too far"),
        ("pin targets count", lambda s: s.set_pins([2, 3], [[0, 0, 0]]), ValueError, "one row per pinned vertex"),
        ("lambda < 0", lambda s: setattr(s, "lam", -0.5), ValueError, "lambda"),
        ("lambda NaN", lambda s: setattr(s, "lam", float("nan")), ValueError, "lambda"),
        ("lambda 1e9", lambda s: setattr(s, "lam", 1e9), ValueError, "lambda"),
        ("admm 0", lambda s: setattr(s, "admm_iterations", 0), ValueError, "ADMM"),
        ("admm -5", lambda s: setattr(s, "admm_iterations", -5), ValueError, "ADMM"),
        ("step -1", lambda s: s.step(-1), ValueError, "steps"),
        ("threads 0", lambda s: gauss_core.set_num_threads(0), ValueError, "threads"),
        ("cube is fine, cone index not", lambda s: (s.set_styles([cube]), s.set_style(3, cone)), ValueError,
         "out of range"),
    ]


@pytest.mark.parametrize("call,exc,words", [c[1:] for c in _bad_calls()], ids=[c[0] for c in _bad_calls()])
def test_bad_call_is_refused_and_changes_nothing(call, exc, words):
    reference, s = gauss_core.Solver(V0, F0), gauss_core.Solver(V0, F0)
    with pytest.raises(exc) as info:
        call(s)
    assert words in str(info.value)
    assert s.factorization_count == reference.factorization_count
    reference.step(4)
    s.step(4)
    np.testing.assert_array_equal(s.vertices, reference.vertices)


# ------------------------------------------------------------------------------------------------
# vertices_into with wrong buffers.

def _bad_out_buffers():
    misaligned = np.frombuffer(bytearray(8 * 3 * NV + 1), dtype=np.uint8, count=8 * 3 * NV, offset=1)
    misaligned = misaligned.view(np.float64).reshape(NV, 3)
    readonly = np.zeros((NV, 3))
    readonly.flags.writeable = False
    return [
        ("(n,2)", np.zeros((NV, 2)), ValueError, "out must have shape"),
        ("(n+1,3)", np.zeros((NV + 1, 3)), ValueError, "out must have shape"),
        ("(3n+1,)", np.zeros(3 * NV + 1), ValueError, "out must have shape"),
        ("(n,3,1)", np.zeros((NV, 3, 1)), ValueError, "out must have shape"),
        ("0-d", np.zeros(()), ValueError, "out must have shape"),
        ("int32", np.zeros((NV, 3), np.int32), TypeError, "dtype float32 or float64"),
        ("int64", np.zeros((NV, 3), np.int64), TypeError, "dtype float32 or float64"),
        ("float16", np.zeros((NV, 3), np.float16), TypeError, "dtype float32 or float64"),
        ("complex", np.zeros((NV, 3), complex), TypeError, "dtype float32 or float64"),
        ("big-endian", np.zeros((NV, 3), ">f8"), TypeError, "dtype float32 or float64"),
        ("strided", np.zeros((NV, 6))[:, ::2], ValueError, "C-contiguous"),
        ("Fortran", np.zeros((NV, 3), order="F"), ValueError, "C-contiguous"),
        ("read-only", readonly, ValueError, "writeable"),
        ("misaligned", misaligned, ValueError, "aligned"),
        ("list", [[0.0] * 3] * NV, TypeError, ""),
        ("None", None, TypeError, ""),
    ]


@pytest.mark.parametrize("out,exc,words", [c[1:] for c in _bad_out_buffers()], ids=[c[0] for c in _bad_out_buffers()])
def test_wrong_out_buffer_is_refused_and_left_alone(out, exc, words):
    s = gauss_core.Solver(V0, F0)
    s.step(2)
    before = np.array(out, copy=True) if isinstance(out, np.ndarray) else None
    with pytest.raises(exc) as info:
        s.vertices_into(out)
    assert words in str(info.value)
    if before is not None:
        np.testing.assert_array_equal(out, before)  # not even partly written


def test_good_out_buffers_receive_the_vertices():
    s = gauss_core.Solver(V0, F0)
    s.step(3)
    expected = s.vertices
    for out in (np.zeros((NV, 3)), np.zeros(3 * NV), np.zeros((NV, 3), np.float32),
                np.zeros((NV, 6))[:, :3].copy(), np.zeros((NV, 3), "<f8")):
        s.vertices_into(out)
        np.testing.assert_allclose(out.reshape(NV, 3), expected, rtol=1e-6 if out.dtype == np.float32 else 0)


# ------------------------------------------------------------------------------------------------
# Odd but valid inputs: same result as clean ones.

def test_lists_non_contiguous_and_other_dtypes_give_the_same_result():
    expected = result(V0, F0, pinned=[0, 7], pin_positions=V0[[0, 7]] + 0.1)
    wide_V = np.zeros((NV, 6))
    wide_V[:, ::2] = V0
    wide_F = np.zeros((NF, 9), np.int64)
    wide_F[:, ::3] = F0
    variants = {
        "lists": (V0.tolist(), F0.tolist(), [0, 7], (V0[[0, 7]] + 0.1).tolist()),
        "strided": (wide_V[:, ::2], wide_F[:, ::3], np.array([9, 0, 9, 7])[1::2], (V0[[0, 7]] + 0.1)[:, :]),
        "Fortran": (np.asfortranarray(V0), np.asfortranarray(F0), (0, 7), np.asfortranarray(V0[[0, 7]] + 0.1)),
        "reversed views": (V0[::-1][::-1], F0[::-1][::-1], np.array([7, 0])[::-1], (V0[[0, 7]] + 0.1)[::-1][::-1]),
        "int32 F": (V0, F0.astype(np.int32), np.array([0, 7], np.int32), V0[[0, 7]] + 0.1),
        "uint16 F": (V0, F0.astype(np.uint16), np.array([0, 7], np.uint8), V0[[0, 7]] + 0.1),
    }
    for name, (V, F, pins, targets) in variants.items():
        got = result(V, F, pinned=pins, pin_positions=targets)
        np.testing.assert_array_equal(got, expected, err_msg=name)
    # float32 input: the same as the float64 input holding the same (rounded) values.
    V32 = V0.astype(np.float32)
    np.testing.assert_array_equal(result(V32, F0), result(V32.astype(np.float64), F0))
    # Integer coordinates are coordinates too.
    Vi = np.round(V0 * 1000).astype(np.int64)
    np.testing.assert_array_equal(result(Vi, F0), result(Vi.astype(np.float64), F0))


def test_zero_steps_and_reset_give_back_the_input():
    s = gauss_core.Solver(V0, F0)
    s.step(0)
    np.testing.assert_allclose(s.vertices, V0, rtol=0, atol=1e-15)
    s.step(3)
    s.reset()
    np.testing.assert_allclose(s.vertices, V0, rtol=0, atol=1e-15)


# ------------------------------------------------------------------------------------------------
# Broken meshes through the module: finite, nothing lost.

def _broken_meshes():
    tri = np.array([[0, 1, 2]])
    loose = np.vstack([V0, [[50.0, -7.25, 1e6], [0.1, 0.2, 0.3]]])  # two vertices no face uses
    fan_V = np.array([[0, 0, 0], [0, 0, 1], [1, 0, 0.5], [-0.5, 0.8, 0.5], [-0.5, -0.8, 0.4]], float)
    separate = np.vstack([V0 + [3 * i, 0, 0] for i in range(5)])
    return {
        "non-manifold fan": (fan_V, np.array([[0, 1, 2], [0, 1, 3], [1, 0, 4]])),
        "duplicate and flipped faces": (V0, np.vstack([F0, F0, F0[:, ::-1]])),
        "repeated-index faces": (V0, np.vstack([F0, [[0, 0, 1], [2, 2, 2]]])),
        "zero-area faces": (np.vstack([V0, V0[F0[0, :2]].mean(0)]), np.vstack([F0, [[F0[0, 0], F0[0, 1], NV]]])),
        "unreferenced vertices": (loose, F0),
        "single triangle": (np.array([[0, 0, 0], [1, 0.1, 0.3], [0.2, 0.9, 0.5]]), tri),
        "open boundary": (V0, F0[: NF // 2]),
        "separate spheres": (separate, np.vstack([F0 + i * NV for i in range(5)])),
        "huge coordinates": (V0 * 1e6 + 3e6, F0),
        "tiny coordinates": (V0 * 1e-6 - 2e-6, F0),
        "float32 input": (V0.astype(np.float32) * 100, F0.astype(np.int32)),
    }


@pytest.mark.parametrize("name", list(_broken_meshes()))
def test_broken_mesh_stylizes_to_finite_coordinates_and_loses_nothing(name):
    V, F = _broken_meshes()[name]
    s = gauss_core.Solver(V, F)
    s.step(15)
    out = s.vertices
    assert out.shape == np.shape(V)
    assert np.isfinite(out).all()
    assert np.isfinite(s.arap_energy) and np.isfinite(s.g_energy)
    used = np.zeros(len(V), bool)
    Fa = np.asarray(F)
    usable = (Fa[:, 0] != Fa[:, 1]) & (Fa[:, 1] != Fa[:, 2]) & (Fa[:, 0] != Fa[:, 2])
    used[Fa[usable].ravel()] = True
    np.testing.assert_array_equal(out[~used], np.asarray(V, np.float64)[~used])  # bit for bit
    size = np.ptp(np.asarray(V, float)[used], axis=0).max()
    center = np.asarray(V, float)[used].mean(0)
    assert np.abs(out[used] - center).max() < 2 * size  # nothing flew away
    f32 = np.empty((len(V), 3), np.float32)
    s.vertices_into(f32)
    assert np.isfinite(f32).all()


def test_a_mesh_without_usable_faces_is_refused_not_crashed():
    for F in (np.zeros((0, 3), np.int64), np.array([[1, 1, 1]]), np.array([[0, 1, 1], [2, 0, 2]])):
        with pytest.raises(ValueError, match="no faces|no usable triangle"):
            gauss_core.Solver(V0, F)
