"""The Sheet Metal style through gauss_core: the preset "sheet_metal" (kind "developable") unbends a
mesh into pieces that bend one way at a time, alone or in one region beside another style."""
import numpy as np

import gauss_core
from measures import developability, style_share
from meshes import icosphere

V, F = icosphere(3)
LAM = gauss_core.PRESET_LAMBDA["sheet_metal"]


def test_the_preset_is_a_developable_style_without_directions():
    s = gauss_core.Style.preset("sheet_metal", sigma=8.0, mu=0.5)
    assert s.kind == "developable" and s.name == "sheet_metal"
    assert len(s.normals) == 0 and not s.ring_offsets and s.sigma == 8.0 and s.mu == 0.5
    assert gauss_core.Style.preset("cube").kind == "directions"


def test_it_unbends_a_sphere():
    # Measured (icosphere(3), 100 steps): developability 0.0035 -> 0.0006, as tests/cpp/test_sheet_metal.cpp.
    s = gauss_core.Solver(V, F, lam=LAM)
    s.set_styles([gauss_core.Style.preset("sheet_metal")])
    s.step(100)
    out = s.vertices
    assert np.isfinite(out).all()
    assert developability(out, F) < developability(V, F) / 4


def test_in_a_region_only_that_region_unbends():
    # Faces on the upper half get the style, the lower half the Cube style. Measured: the upper half's
    # developability 0.0030 -> 0.00058.
    up = V[F].mean(axis=1)[:, 2] > 0
    s = gauss_core.Solver(V, F, lam=LAM)
    s.set_styles([gauss_core.Style.preset("sheet_metal"), gauss_core.Style.preset("cube")])
    s.set_face_styles(np.where(up, 0, 1))
    s.step(100)
    out = s.vertices
    upper = F[up.nonzero()[0]]
    assert developability(out, upper) < developability(V, upper) / 3


def _tube(around=24, along=6):
    """An open cylinder of radius 1 and height 2: rolled sheet, developable everywhere."""
    a = 2 * np.pi * np.arange(around) / around
    V = np.array([[np.cos(t), np.sin(t), 2.0 * j / along] for j in range(along + 1) for t in a])
    F = []
    for j in range(along):
        for i in range(around):
            p, q = j * around + i, j * around + (i + 1) % around
            F += [[p, q, q + around], [p, q + around, p + around]]
    return V, np.array(F)


def test_the_quality_share_of_a_developable_style_counts_faces_on_one_great_circle():
    # style_share's measure for Sheet Metal (the quality matrix's share): a rolled sheet reaches it
    # everywhere, a sphere nowhere, and the style's run raises it.
    style = gauss_core.Style.preset("sheet_metal")
    tube_V, tube_F = _tube()
    assert style_share(tube_V, tube_F, style) == 1.0
    assert style_share(V, F, style) == 0.0
    s = gauss_core.Solver(V, F, lam=LAM)
    s.set_styles([style])
    s.step(100)
    assert style_share(s.vertices, F, style) > 0.5
