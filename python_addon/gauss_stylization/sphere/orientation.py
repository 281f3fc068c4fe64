"""The rotation of a style under which a surface already fits it best (numpy only).

Fit of a rotation R: F(R) = sum_i w_i g(R^T n_i) / sum_i w_i, the area-weighted
mean of the unrotated style's g over the surface's normals n_i, when
the style's preferred normals are turned by R (so a face normal n meets the
unrotated style at R^T n). F is smooth but has many maxima (every symmetry of the
style or of the surface gives one), so the search is global then local:

1. a grid over SO(3) (a super-Fibonacci spiral of unit quaternions, Alexa 2022)
   evaluated on coarsely binned normals (and the style at a sigma of at most
   SEARCH_SIGMA, so narrow bumps are not stepped over); its local maxima are the seeds;
2. each seed climbs to its maximum on the coarse normals (a damped Newton method
   with F's analytic gradient and Hessian, from the style's), the best few again
   on finely binned normals with the style as it is;
3. among those whose fit equals the best (up to ``TIE``), the one with the smallest
   rotation angle wins, and it is then moved closer to no rotation while the fit
   stays the best: along a continuous symmetry (the rings of a cylinder or cone
   style turn about their axis without changing the fit) or to a nearer copy of a
   discrete one (a cube style fits a cube in 24 ways).
"""

import numpy as np

from .directions import binned

GRID_SIZE = 4000            # quaternions: ~12 degrees between neighbouring rotations
SEARCH_SIGMA = 16.0         # bumps of g about 14 degrees wide: the grid cannot step over them
NEIGHBOURHOOD = np.radians(20.0)  # a grid point no other this close beats is a seed
SEEDS = 48                  # at most this many seeds (the best) are refined
COARSE_DEGREES = 8.0        # normals binned this coarsely for the grid and the first refinement
FINE_DEGREES = 2.0          # ... and this finely for the final one
COARSE_END = np.radians(0.05)     # the coarse fit cannot place a maximum better than this
END_STEP = np.radians(0.001)      # steps shorter than this end a refinement
NEWTON_ITERATIONS = 100     # at most this many tries of a refinement
NEWTON_MAX_TURN = np.radians(5.0)  # the largest turn one step takes about each principal direction
NEWTON_MIN_GAIN = 1e-13     # a step raising the fit less than this (rounding) ends Newton's method
TIE = 1e-5                  # fits (mean g) closer than this are equally good
DESCENT_TIE = 1e-7          # how much fit the last search may give up for a smaller angle
COARSE_TIE = 1e-2           # ... as far as the coarsely binned normals can tell
MAX_FINALISTS = 6           # maxima polished on the fine normals (plus the one with the smallest angle)
SAME_ANGLE = np.radians(1.0)  # refined seeds closer than this reached the same maximum
MIN_FRACTION = 1.0 / 64     # the smallest part of the way back to no rotation tried
CHUNK = 256                 # rotations evaluated per call of ``value``


def super_fibonacci(count):
    """``count`` unit quaternions (w, x, y, z) spread evenly over S^3 (count by 4)."""
    phi, psi = np.sqrt(2.0), 1.533751168755204288118041
    s = np.arange(count) + 0.5
    r, big_r = np.sqrt(s / count), np.sqrt(1.0 - s / count)
    alpha, beta = 2.0 * np.pi * s / phi, 2.0 * np.pi * s / psi
    return np.stack([r * np.sin(alpha), r * np.cos(alpha), big_r * np.sin(beta), big_r * np.cos(beta)], axis=1)


def quaternion_matrices(q):
    """Rotation matrices (N by 3 by 3) of unit quaternions q (N by 4, w first)."""
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
    ], axis=1)


def axis_angle_matrices(vectors):
    """exp([v]x): rotations (N by 3 by 3) by |v| radians about v (N by 3)."""
    vectors = np.asarray(vectors, np.float64).reshape(-1, 3)
    angle = np.linalg.norm(vectors, axis=1)
    half = 0.5 * angle
    scale = np.where(angle > 0, np.sin(half) / np.where(angle > 0, angle, 1.0), 0.5)
    return quaternion_matrices(np.column_stack([np.cos(half), vectors * scale[:, None]]))


def rotation_angle(matrix):
    """Angle (radians) of a rotation matrix (3 by 3, or N by 3 by 3)."""
    trace = np.trace(matrix, axis1=-2, axis2=-1)
    return np.arccos(np.clip((trace - 1.0) / 2.0, -1.0, 1.0))


AXIS_WORDS_DEGREES = 10.0  # a direction this close to an axis is called after the axis


def direction_in_words(vector):
    """'+X', '-Z' for a direction within AXIS_WORDS_DEGREES of an axis, else '(0.58, -0.58, 0.58)'."""
    vector = np.asarray(vector, np.float64) / np.linalg.norm(vector)
    k = int(np.argmax(np.abs(vector)))
    if abs(vector[k]) >= np.cos(np.radians(AXIS_WORDS_DEGREES)):
        return "%s%s" % ("-" if vector[k] < 0 else "+", "XYZ"[k])
    return "(%.2f, %.2f, %.2f)" % tuple(vector)


def rotation_in_words(matrix):
    """A rotation (3 by 3, the style's frame -> the object's) as an artist reads it: the axis it
    turns about and where each of the style's axes now lies in the object, e.g. "90.0 degrees
    about -X: the style's axes X along +X, Y along -Z, Z along +Y"."""
    matrix = np.asarray(matrix, np.float64)
    angle = float(rotation_angle(matrix))
    if angle < np.radians(0.05):
        return "not turned: the style's axes lie along the object's"
    axis = np.array([matrix[2, 1] - matrix[1, 2], matrix[0, 2] - matrix[2, 0], matrix[1, 0] - matrix[0, 1]])
    if np.linalg.norm(axis) < 1e-6:  # a half turn: the axis is the eigenvector of eigenvalue 1
        values, vectors = np.linalg.eigh(matrix + matrix.T)
        axis = vectors[:, int(np.argmax(values))]
    lying = ", ".join("%s along %s" % (name, direction_in_words(matrix[:, i])) for i, name in enumerate("XYZ"))
    return "%.1f degrees about %s: the style's axes %s" % (np.degrees(angle), direction_in_words(axis), lying)


def _skew(vectors):
    """[v]x of each row of vectors (N by 3) -> N by 3 by 3."""
    out = np.zeros((len(vectors), 3, 3))
    out[:, 0, 1], out[:, 0, 2], out[:, 1, 2] = -vectors[:, 2], vectors[:, 1], -vectors[:, 0]
    return out - out.transpose(0, 2, 1)


class Fit:
    """F(R) for one style and one weighted set of unit normals (N by 3, weights N).

    style: the unrotated gauss_core.Style (value, gradient, hessian of g)."""

    def __init__(self, style, normals, weights):
        self.style, self.value = style, style.value
        self.normals = np.asarray(normals, np.float64)
        self.weights = np.asarray(weights, np.float64) / np.sum(weights)
        self.skew = _skew(self.normals)

    def __call__(self, rotations):
        """Fits of rotations (M by 3 by 3) -> M."""
        rotations = np.asarray(rotations, np.float64).reshape(-1, 3, 3)
        out = np.empty(len(rotations))
        for start in range(0, len(rotations), CHUNK):
            part = rotations[start:start + CHUNK]
            # Row i of normals @ R is (R^T n_i)^T: the normal in the unrotated style's frame.
            turned = np.einsum("nj,rjk->rnk", self.normals, part)
            values = np.asarray(self.value(turned.reshape(-1, 3)), np.float64).reshape(len(part), -1)
            out[start:start + len(part)] = values @ self.weights
        return out

    def derivatives(self, rotation):
        """F, its gradient (3,) and Hessian (3 by 3) at ``rotation`` with respect to w, where
        exp([w]x) R turns the style further.

        With x = R^T n the normal in the style's frame, G = R grad g(x) and H = R Hess g(x) R^T
        (g's derivatives in space, which the style gives), R^T exp(-[w]x) n to second order:
            gradient = sum w_i G_i x n_i
            Hessian  = sum w_i (sym(G_i n_i^T) - (G_i . n_i) I - [n_i]x H_i [n_i]x)
        """
        turned = self.normals @ rotation
        gradient = np.asarray(self.style.gradient(turned)) @ rotation.T
        hessian = rotation @ np.asarray(self.style.hessian(turned)) @ rotation.T
        value = np.asarray(self.value(turned)) @ self.weights
        w = self.weights
        first = w @ np.cross(gradient, self.normals)
        outer = np.einsum("n,ni,nj->ij", w, gradient, self.normals)
        curved = (w @ (self.skew @ hessian @ self.skew).reshape(-1, 9)).reshape(3, 3)
        second = 0.5 * (outer + outer.T) - np.eye(3) * (w @ np.einsum("ij,ij->i", gradient, self.normals)) - curved
        return value, first, second


def polish(fit, rotation, end=None):
    """Levenberg-Marquardt's method on ``fit`` from ``rotation``: (rotation, fit) at a maximum.

    Newton steps on the fit's second-order model, damped by ``damping`` (plus whatever
    makes the model concave: away from the top, or along a continuous symmetry), at most
    NEWTON_MAX_TURN radians. A step that raises the fit is taken and the damping lowered;
    one that does not raises the damping. Ends when the model expects less than
    NEWTON_MIN_GAIN, or steps get shorter than ``end`` radians (default END_STEP)."""
    end = END_STEP if end is None else end
    value, gradient, hessian = fit.derivatives(rotation)
    damping = None
    for _ in range(NEWTON_ITERATIONS):
        curvature, axes = np.linalg.eigh(-hessian)
        if damping is None:
            damping = 1e-3 * max(np.abs(curvature).max(), 1e-12)
        shift = max(0.0, -curvature.min()) + damping
        # Each principal direction's turn is limited on its own: along a symmetry (no
        # curvature) a large turn changes nothing and must not shorten the others.
        turns = np.clip((axes.T @ gradient) / (curvature + shift), -NEWTON_MAX_TURN, NEWTON_MAX_TURN)
        step = axes @ turns
        if gradient @ step < NEWTON_MIN_GAIN or np.linalg.norm(step) < end:
            break
        candidate = axis_angle_matrices(step)[0] @ rotation
        if fit(candidate[None])[0] > value + NEWTON_MIN_GAIN:
            rotation = candidate
            value, gradient, hessian = fit.derivatives(rotation)
            damping *= 0.3
        else:
            damping *= 4.0
    return rotation, value


def rotation_vector(matrix):
    """Axis times angle (3,) of a rotation matrix (3 by 3); the inverse of axis_angle_matrices."""
    angle = rotation_angle(matrix)
    skew = np.array([matrix[2, 1] - matrix[1, 2], matrix[0, 2] - matrix[2, 0], matrix[1, 0] - matrix[0, 1]])
    if angle < 1e-12:
        return 0.5 * skew
    if np.pi - angle > 1e-6:
        return skew * (angle / (2.0 * np.sin(angle)))
    # Half a turn: the axis is the column of R + I with the largest norm.
    columns = matrix + np.eye(3)
    axis = columns[:, int(np.argmax(np.linalg.norm(columns, axis=0)))]
    return axis / np.linalg.norm(axis) * angle


def _closer_to_identity(coarse, fine, rotation, best):
    """The rotation with the smallest angle whose fine fit stays within DESCENT_TIE of ``best``,
    found by turning part of the way back to no rotation and climbing to the nearest
    maximum again: this walks along a continuous symmetry (a ring style turned about
    its axis) and jumps to a nearer copy of a discrete one. Each try climbs on the
    coarse fit first; only a try that lands closer to no rotation is polished."""
    fraction = 0.5
    while fraction > MIN_FRACTION:
        start = axis_angle_matrices(rotation_vector(rotation) * (1.0 - fraction))[0]
        candidate = polish(coarse, start, end=COARSE_END)[0]
        accepted = False
        if rotation_angle(candidate) < rotation_angle(rotation) - SAME_ANGLE / 10:
            candidate, value = polish(fine, candidate)
            accepted = value >= best - DESCENT_TIE and rotation_angle(candidate) < rotation_angle(rotation)
        if accepted:
            rotation = candidate
        else:
            fraction *= 0.5
    return rotation


def _local_maxima(quaternions, fits, radius):
    """Indices of grid points whose fit no neighbour (rotation angle below ``radius``) beats."""
    cos_half = np.cos(radius / 2.0)
    keep = []
    for start in range(0, len(quaternions), 512):
        near = np.abs(quaternions[start:start + 512] @ quaternions.T) >= cos_half
        better = near & (fits[None, :] > fits[start:start + 512, None])
        keep.extend(start + np.flatnonzero(~better.any(axis=1)))
    return np.array(keep, int)


def best_rotation(style, normals, weights, search_style=None):
    """The rotation (3 by 3) that turns a style so the surface fits it best, the smallest
    such rotation among equally good ones, and its fit (mean g).

    style:        the unrotated gauss_core.Style
    normals:      the surface's unit normals (#T by 3); weights: their areas (#T, some > 0)
    search_style: the same style with a lower sigma (at most SEARCH_SIGMA) for the coarse
                  stages, whose grid would miss a high sigma's narrow bumps; default: ``style``
    """
    normals, weights = np.asarray(normals, np.float64), np.asarray(weights, np.float64)
    used = weights > 0
    if not used.any():
        raise ValueError("the surface has no area to fit a style to")
    normals, weights = normals[used], weights[used]
    coarse = Fit(search_style or style, *binned(normals, weights, COARSE_DEGREES))
    fine = Fit(style, *binned(normals, weights, FINE_DEGREES))

    quaternions = super_fibonacci(GRID_SIZE)
    grid = quaternion_matrices(quaternions)
    fits = coarse(grid)
    maxima = _local_maxima(quaternions, fits, NEIGHBOURHOOD)
    seeds = [grid[i] for i in maxima[np.argsort(-fits[maxima], kind="stable")][:SEEDS]] + [np.eye(3)]
    refined = [polish(coarse, seed, end=COARSE_END) for seed in seeds]
    best_coarse = max(f for _, f in refined)
    # The coarse fit only approximates the fine one: every maximum it cannot tell from
    # the best is polished on the fine normals (once: seeds often climb to the same one).
    finalists = []
    for rotation, f in sorted(refined, key=lambda pair: -pair[1]):
        if f >= best_coarse - COARSE_TIE and all(
                rotation_angle(rotation @ other.T) > SAME_ANGLE for other in finalists):
            finalists.append(rotation)
    # Symmetric copies of one maximum (a cube mesh, a ring style) all tie; a few of them
    # and the one with the smallest angle suffice: the last step finds nearer copies.
    nearest = min(range(len(finalists)), key=lambda i: rotation_angle(finalists[i]))
    finalists = [finalists[i] for i in sorted(set(range(min(MAX_FINALISTS, len(finalists)))) | {nearest})]
    finals = [polish(fine, rotation) for rotation in finalists]
    best = max(f for _, f in finals)
    if fine(np.eye(3)[None])[0] >= best - TIE:  # already fits: no rotation at all
        return np.eye(3), best
    smallest = min((rotation for rotation, f in finals if f >= best - TIE), key=rotation_angle)
    smallest = _closer_to_identity(coarse, fine, smallest, best)
    return smallest, fine(smallest[None])[0]
