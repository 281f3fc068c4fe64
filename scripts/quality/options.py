"""The quality matrix's options: one row per method, style or setting it judges on every mesh.

A new look or setting is one more row of OPTIONS. A row names its style preset, method, lambda and
the Solver keywords it turns on, and optionally painted face weights and pins (functions of the mesh,
below). `tags` select rows on the command line (--options) and name the rows whose thresholds are
regenerated together ('guard': Avoid Self-Intersections, 'paint': painted strength). `plain` names the
row the same run without the option is, to compare shares with.
"""
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np


def longest_axis_position(V):
    """Each vertex's position along the bounding box's longest axis, 0 at its low end, 1 at its high end."""
    low, high = V.min(axis=0), V.max(axis=0)
    axis = int(np.argmax(high - low))
    return (V[:, axis] - low[axis]) / max(high[axis] - low[axis], 1e-300)


def uniform_weight(w):
    def weights(V, F):
        return np.full((len(F), 1), w)
    weights.__doc__ = f"every face painted {w}"
    return weights


def gradient_weights(V, F):
    """Faces painted from 0 at the low end of the longest axis to 1 at its high end (by their corners' mean)."""
    return longest_axis_position(V)[F].mean(axis=1)[:, None]


def lowest_vertices(fraction):
    def pins(V, F):
        used = np.unique(F)
        t = longest_axis_position(V)[used]
        return np.sort(used[np.argsort(t, kind="stable")[:max(1, int(round(fraction * len(used))))]])
    pins.__doc__ = f"the lowest {fraction:.0%} of the vertices along the longest axis pinned"
    return pins


@dataclass(frozen=True)
class Option:
    name: str
    preset: str = "cube"
    method: str = "gauss"
    lam: Optional[float] = None  # None: the preset's gauss_core.PRESET_LAMBDA, else DEFAULTS['lam']
    sigma: Optional[float] = None  # None: the preset's own
    keywords: dict = field(default_factory=dict)  # more gauss_core.Solver keywords
    weights: Optional[Callable] = None  # (V, F) -> (#F, 1) face weights for set_face_weights
    pins: Optional[Callable] = None  # (V, F) -> pinned vertex indices
    fast: bool = True  # in the --fast subset
    tags: tuple = ()
    plain: Optional[str] = None


GUARD = {"avoid_self_intersections": True}
SQUARE = {"square_flat_regions": True}
INDEPENDENT = {"resolution_independent": True}  # the add-on's default for new objects

OPTIONS = [
    Option("cube"),
    Option("tetrahedron l10", preset="tetrahedron", lam=10.0),
    Option("cylinder", preset="cylinder"),
    # Its side normals stand between a box's: a box does not settle under it (docs/limitations.md).
    Option("triangular prism", preset="triangular_prism"),
    Option("cubic", method="cubic"),
    Option("cube +avoid", keywords=GUARD, tags=("guard",), plain="cube"),
    Option("tetrahedron l10 +avoid", preset="tetrahedron", lam=10.0, keywords=GUARD, tags=("guard",),
           plain="tetrahedron l10"),
    Option("cube +keep volume", keywords={"keep_volume": True}),
    Option("cube +independent", keywords=INDEPENDENT, tags=("independent",), plain="cube"),
    Option("tetrahedron l10 +independent", preset="tetrahedron", lam=10.0, keywords=INDEPENDENT,
           tags=("independent",), plain="tetrahedron l10"),
    # Painted as an artist paints a new object: with Resolution Independent, against the same run unpainted.
    Option("cube painted 0.5", weights=uniform_weight(0.5), keywords=INDEPENDENT, tags=("paint",),
           plain="cube +independent"),
    Option("cube painted 0-1", weights=gradient_weights, keywords=INDEPENDENT, tags=("paint",),
           plain="cube +independent"),
    Option("cube pinned 5%", pins=lowest_vertices(0.05), plain="cube"),
    # Sharper than gauss_core.PAPER_STEP_MAX_SIGMA: the normal's step taken on the sphere.
    Option("cube sigma 12", sigma=12.0, tags=("sigma",), plain="cube"),
    Option("tetrahedron sigma 20", preset="tetrahedron", sigma=20.0, tags=("sigma",), fast=False),
    Option("sheet metal", preset="sheet_metal"),
    Option("cube +square flat", keywords=SQUARE, tags=("square",), plain="cube"),
    Option("cubic +square flat", method="cubic", keywords=SQUARE, tags=("square",), plain="cubic"),
]


def select(names_or_tags, fast):
    """The rows named (by name or tag, comma-separated; None: all), of the fast subset if `fast`."""
    rows = [o for o in OPTIONS if o.fast or not fast]
    if names_or_tags:
        wanted = {w.strip() for w in names_or_tags.split(",")}
        unknown = wanted - {o.name for o in OPTIONS} - {t for o in OPTIONS for t in o.tags}
        if unknown:
            raise SystemExit(f"unknown option(s) {sorted(unknown)}; rows: {[o.name for o in OPTIONS]}")
        rows = [o for o in rows if o.name in wanted or wanted & set(o.tags)]
    return rows


def by_name(name):
    return next(o for o in OPTIONS if o.name == name)
