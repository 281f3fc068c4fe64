"""Painted weight -> strength: the curve that makes a Region's paint act about linearly.

How much a face turns towards its style grows fast with a small strength and then saturates
(a quarter of the mu gives most of the effect), about linearly in the logarithm of the strength
over two decades. So a face's total painted weight t in [0, 1] scales its styles' mu by

    strength(t) = (exp(K t) - 1) / (exp(K) - 1),   exactly 0 at t = 0 and exactly 1 at t = 1,

exponential in the weight, which gives a share of aligned faces close to linear in t on every mesh
and lambda measured (docs/interactive.md#painting-the-strength has the curve's derivation and the
table). numpy only: scripts/measure_paint_response.py loads it by path.
"""

import numpy as np

K = 5.6  # docs/interactive.md#painting-the-strength: how it was chosen


def strength(total):
    """(n,) painted weights in [0, 1] -> mu scales in [0, 1] (float64)."""
    total = np.clip(np.asarray(total, np.float64), 0.0, 1.0)
    return np.expm1(K * total) / np.expm1(K)


def scale_blend(weights):
    """(n, #slots) weights of a face's slots (Regions plus the slot that takes what they leave) ->
    the same with the curve applied to each face's total: where the total is below 1 every slot's
    weight is scaled by strength(total) / total, so the mix of styles stays and only how strongly
    the face is stylized follows the curve; a total of 1 or more (a slot filled the rest, or Regions
    overlap) is left exactly as it is."""
    weights = np.asarray(weights, np.float64)
    total = weights.sum(axis=1)
    below = total < 1.0
    factor = np.ones_like(total)
    factor[below] = strength(total[below]) / np.maximum(total[below], 1e-300)  # 0 where the total is 0
    return np.where(below[:, None], weights * factor[:, None], weights)
