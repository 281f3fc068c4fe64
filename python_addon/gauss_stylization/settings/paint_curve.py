"""Painted weight -> strength: the curve that makes a Region's paint act about linearly.

With the Gauss method, how far a face turns towards its style grows with the pull lambda * (mu
scale) roughly as the logarithm of that pull: nothing shows below a small pull, and above it a
small part of the full pull already gives most of the effect. So a face's total painted weight t
in [0, 1] scales its styles' mu by

    strength(t) = (exp(k t) - 1) / (exp(k) - 1),   k = ln(lambda / pull_shown)

(exactly 0 at t = 0 and exactly 1 at t = 1): from t = 0 to 1 the pull climbs log-uniformly from
about the pull where the style starts to show to the full lambda. That onset is higher with
Resolution Independent, which stiffens the bending of meshes finer than its reference density (Spot,
the bunnies). The Cubic method's response to its strength is already close to linear, so it takes the
weights as they are (k = 0). How the constants were measured and what the curve gives:
docs/interactive.md#the-paint-curve. numpy only: scripts/measure_paint_response.py and the quality
matrix load it by path.
"""

import math

import numpy as np

# lambda * mu scale where a Gauss style starts to show (docs/interactive.md#the-paint-curve): the paper's
# method, and with Resolution Independent (unless the object keeps the curve it was saved with, old_paint_curve).
PULL_SHOWN = 0.025
PULL_SHOWN_INDEPENDENT = 0.05
_LINEAR = 1e-6      # below this steepness the curve is the straight line it tends to


def pull_shown(resolution_independent, old_paint_curve=False):
    """Where the style starts to show, for an object's Resolution Independent and old_paint_curve."""
    return PULL_SHOWN_INDEPENDENT if resolution_independent and not old_paint_curve else PULL_SHOWN


def steepness(method, lam, pull):
    """k of the curve for a method ('GAUSS', 'CUBIC': the enum identifiers) at Lambda ``lam``, the
    style starting to show at the pull ``pull`` (pull_shown: no default, since it depends on the
    object's Resolution Independent; the add-on calls steepness_of)."""
    if method != 'GAUSS' or not lam > pull:
        return 0.0
    return math.log(lam / pull)


def steepness_of(settings):
    """k of the curve for an object's settings (GaussSettings, or anything with its attributes)."""
    return steepness(settings.method, settings.lam,
                     pull_shown(settings.resolution_independent, settings.old_paint_curve))


def strength(total, k):
    """(n,) painted weights in [0, 1] -> mu scales in [0, 1] (float64)."""
    total = np.clip(np.asarray(total, np.float64), 0.0, 1.0)
    if k < _LINEAR:
        return total
    return np.expm1(k * total) / np.expm1(k)


def scale_blend(weights, k):
    """(n, #slots) weights of each face's slots -> the same with the curve applied to each face's
    total: where the total is below 1 every slot's weight is scaled by strength(total) / total, so
    the mix of styles stays and only how strongly the face is stylized follows the curve; a total of
    1 or more (Regions that overlap) is left exactly as it is."""
    weights = np.asarray(weights, np.float64)
    total = weights.sum(axis=1)
    below = total < 1.0
    factor = np.ones_like(total)
    factor[below] = strength(total[below], k) / np.maximum(total[below], 1e-300)  # 0 where the total is 0
    return np.where(below[:, None], weights * factor[:, None], weights)
