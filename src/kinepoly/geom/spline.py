"""A closed smooth curve through given points: the periodic cubic spline of a ``points`` cam profile.

The curve is r(u) = x(u) + i y(u), a complex cubic on each piece between two consecutive points,
with u the chord length (u_k = |P_1 P_0| + ... + |P_k P_(k-1)|, the period L the closed polygon's
perimeter), so that points spaced unevenly still give a curve without loops. The second
derivatives M_k at the points solve the periodic system (one row per point, indices modulo n)

    h_(k-1) M_(k-1) + 2 (h_(k-1) + h_k) M_k + h_k M_(k+1) = 6 ((P_(k+1) - P_k) / h_k - (P_k - P_(k-1)) / h_(k-1))

and the piece from P_k is a + b t + c t^2 + d t^3 (0 <= t <= h_k) with a = P_k,
b = (P_(k+1) - P_k) / h_k - h_k (2 M_k + M_(k+1)) / 6, c = M_k / 2, d = (M_(k+1) - M_k) / (6 h_k):
the curve, its tangent and its curvature are continuous all round, the last piece closing on P_0.

Accuracy, for points sampled from a smooth closed curve at spacing h: the point is off the curve
by O(h^4), the tangent's direction by O(h^3), the curvature by O(h^2) (measured in
``tests/geom/test_spline_geometry.py``; ``docs/scene-format.md`` states the figures).

Every evaluation is over a numpy array of parameters (any shape; u is taken modulo L). Curvature is
positive where the curve turns counter-clockwise, the centre of curvature on the left of the tangent.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt
from msgspec import Struct

from kinepoly.geom.arrays import Bools, Points, Reals
from kinepoly.geom.tolerances import STRAIGHT_CURVATURE

__all__ = [
    "CurveFrame",
    "PeriodicSpline",
    "nearest_parameter",
    "periodic_spline",
    "roots_along",
    "roots_by_row",
    "signed_area",
]

_STRAIGHT_CURVATURE = STRAIGHT_CURVATURE
"""A curvature below this times 1/L (L the period) is a straight stretch: its centre is at infinity."""
_FOOT_SAMPLES_PER_PIECE = 64
"""Samples of each piece among which ``nearest_parameter`` starts from the nearest."""
_FOOT_STEPS = 8
"""Newton steps that settle ``nearest_parameter`` (quadratic: a few suffice from the nearest sample)."""
_BISECTIONS = 200
"""Most halvings of a bracket; each root is settled after about 50 (see ``roots_along``)."""


class PeriodicSpline(Struct, frozen=True):
    """A closed periodic cubic spline: ``knots[k]`` is the parameter of point k (``knots[n]`` the
    period), and piece k is ``coefficients[k, 0] + coefficients[k, 1] t + ... + coefficients[k, 3] t^3``."""

    knots: Reals
    coefficients: Points

    @property
    def period(self) -> float:
        """L, the parameter once round the curve (the perimeter of the polygon through the points)."""
        return float(self.knots[-1])

    @property
    def pieces(self) -> int:
        return int(self.coefficients.shape[0])

    def _locate(self, u: Reals) -> tuple[npt.NDArray[np.intp], Reals]:
        wrapped = np.mod(np.asarray(u, dtype=np.float64), self.period)
        piece = np.clip(np.searchsorted(self.knots, wrapped, side="right") - 1, 0, self.pieces - 1)
        return piece, wrapped - self.knots[piece]

    def derivatives(self, u: Reals | float) -> tuple[Points, Points, Points]:
        """r(u), r'(u) and r''(u), each an array of the shape of ``u``."""
        piece, t = self._locate(np.asarray(u, dtype=np.float64))
        a, b, c, d = (self.coefficients[piece, j] for j in range(4))
        point = a + t * (b + t * (c + t * d))
        first = b + t * (2.0 * c + 3.0 * t * d)
        second = 2.0 * c + 6.0 * t * d
        return point, first, second

    def point(self, u: Reals | float) -> Points:
        return self.derivatives(u)[0]

    def frame(self, u: Reals | float) -> CurveFrame:
        """The point, unit tangent, unit normal (the tangent turned a quarter turn counter-clockwise) and
        curvature at ``u``."""
        point, first, second = self.derivatives(u)
        speed = np.abs(first)
        tangent = first / speed
        curvature = np.imag(np.conj(first) * second) / speed**3
        return CurveFrame(point, tangent, 1j * tangent, curvature, 1.0 / self.period)

    def sample(self, count: int) -> Points:
        """``count`` points at equal steps of the parameter, from P_0 counter-clockwise, not closed."""
        return self.point(self.period * np.arange(count) / count)



class CurveFrame(Struct, frozen=True):
    """The curve's local frame at an array of parameters."""

    point: Points
    tangent: Points
    normal: Points
    curvature: Reals
    scale: float
    """1/L: below ``_STRAIGHT_CURVATURE * scale`` a curvature counts as zero."""

    @property
    def is_straight(self) -> Bools:
        """Where the curve is (numerically) straight: the centre of curvature is at infinity."""
        return np.asarray(np.abs(self.curvature) <= _STRAIGHT_CURVATURE * self.scale)

    @property
    def centre_of_curvature(self) -> Points:
        """point + normal / curvature; where ``is_straight``, the point itself (mask those rows)."""
        bent = ~self.is_straight
        safe = np.where(bent, self.curvature, 1.0)
        return np.where(bent, self.point + self.normal / safe, self.point)


def signed_area(points: Sequence[tuple[float, float]]) -> float:
    """The signed area of the closed polygon through ``points`` (positive: counter-clockwise)."""
    z = np.array([complex(x, y) for x, y in points])
    return float(0.5 * np.sum(np.imag(np.conj(z) * np.roll(z, -1))))


def periodic_spline(points: Sequence[tuple[float, float]]) -> PeriodicSpline:
    """The periodic cubic spline through ``points`` (at least 3, consecutive points distinct, the first not
    repeated at the end) with chord-length parameter."""
    z = np.array([complex(x, y) for x, y in points])
    n = len(z)
    if n < 3:
        raise ValueError(f"a closed spline needs at least 3 points, got {n}")
    chord = np.abs(np.roll(z, -1) - z)
    if not np.all(chord > 0.0):
        raise ValueError("two consecutive points of a closed spline coincide")
    knots = np.concatenate(([0.0], np.cumsum(chord)))
    h = chord
    h_before = np.roll(h, 1)
    slope = (np.roll(z, -1) - z) / h
    rhs = 6.0 * (slope - np.roll(slope, 1))
    second = _solve_cyclic(h_before, 2.0 * (h_before + h), h, rhs)
    second_next = np.roll(second, -1)
    coefficients = np.stack([z, slope - h * (2.0 * second + second_next) / 6.0, second / 2.0,
                             (second_next - second) / (6.0 * h)], axis=1)
    return PeriodicSpline(knots, coefficients)


def _solve_cyclic(lower: Reals, diagonal: Reals, upper: Reals, rhs: Points) -> Points:
    """x with lower[k] x[k-1] + diagonal[k] x[k] + upper[k] x[k+1] = rhs[k], indices modulo n.

    The matrix is strictly diagonally dominant (2 (h_(k-1) + h_k) > h_(k-1) + h_k), so the cyclic
    Thomas algorithm (Sherman-Morrison on the corner entries) needs no pivoting."""
    n = len(diagonal)
    gamma = -diagonal[0]
    diag = diagonal.astype(np.float64).copy()
    diag[0] -= gamma
    diag[-1] -= lower[0] * upper[-1] / gamma
    u = np.zeros(n, dtype=np.complex128)
    u[0], u[-1] = gamma, upper[-1]
    y = _thomas(lower, diag, upper, rhs.astype(np.complex128))
    q = _thomas(lower, diag, upper, u)
    v_dot_y = y[0] + lower[0] / gamma * y[-1]
    v_dot_q = q[0] + lower[0] / gamma * q[-1]
    return np.asarray(y - q * (v_dot_y / (1.0 + v_dot_q)))


def _thomas(lower: Reals, diagonal: Reals, upper: Reals, rhs: Points) -> Points:
    """The tridiagonal solve (corner entries ignored) by forward elimination and back substitution."""
    n = len(diagonal)
    c = np.zeros(n)
    d = np.zeros(n, dtype=np.complex128)
    c[0], d[0] = upper[0] / diagonal[0], rhs[0] / diagonal[0]
    for k in range(1, n):
        pivot = diagonal[k] - lower[k] * c[k - 1]
        c[k] = upper[k] / pivot
        d[k] = (rhs[k] - lower[k] * d[k - 1]) / pivot
    for k in range(n - 2, -1, -1):
        d[k] -= c[k] * d[k + 1]
    return d


def roots_along(spline: PeriodicSpline, function: Callable[[Reals], Reals], per_piece: int = 8) -> Reals:
    """The parameters in [0, L) where ``function`` (over arrays of parameters) changes sign, each to
    the last bit of the parameter, sorted (``roots_by_row`` for one row)."""
    return roots_by_row(spline, lambda _, u: function(u), 1, per_piece)[1]


def roots_by_row(spline: PeriodicSpline, function: Callable[[npt.NDArray[np.intp], Reals], Reals], rows: int,
                 per_piece: int = 8) -> tuple[npt.NDArray[np.intp], Reals]:
    """The roots of one function of the parameter per row: ``function(row, u)`` (arrays of one shape) changes
    sign at each returned (row, u), u in [0, L) to the last bit, sorted by row and then by u.

    Each piece is sampled at ``per_piece`` equal steps; every sign change brackets one root, refined
    by bisection, all brackets of all rows at once (about 50 halvings: safe where Newton's step could
    leave the bracket, and cheap over arrays). A root where the function touches zero without
    changing sign (a grazing contact) is not found: it is a dead point, not an assembly."""
    step = np.diff(spline.knots)[:, None] * (np.arange(per_piece) / per_piece)[None, :]
    grid = (spline.knots[:-1, None] + step).ravel()
    every = np.arange(rows)[:, None] + np.zeros(len(grid), np.intp)[None, :]
    values = function(every, np.broadcast_to(grid, every.shape))
    after = np.roll(values, -1, axis=1)
    exact = values == 0.0
    row, column = np.nonzero((np.sign(values) * np.sign(after) < 0.0) & ~exact)
    low = grid[column]
    high = np.where(column == len(grid) - 1, spline.period, grid[(column + 1) % len(grid)])
    f_low = values[row, column]
    for _ in range(_BISECTIONS):
        if low.size == 0 or np.all(high - low <= 4.0 * np.spacing(np.maximum(np.abs(high), 1.0))):
            break
        mid = 0.5 * (low + high)
        f_mid = function(row, mid)
        left = np.sign(f_mid) == np.sign(f_low)
        low, f_low = np.where(left, mid, low), np.where(left, f_mid, f_low)
        high = np.where(left, high, mid)
    exact_row, exact_column = np.nonzero(exact)
    all_rows = np.concatenate((exact_row, row))
    roots = np.mod(np.concatenate((grid[exact_column], 0.5 * (low + high))), spline.period)
    order = np.lexsort((roots, all_rows))
    return all_rows[order], roots[order]

def nearest_parameter(spline: PeriodicSpline, point: complex, offset: float = 0.0) -> float:
    """The parameter u of the point of the curve X(u) = r(u) + ``offset`` n(u) (n the unit left normal) nearest
    ``point``: the nearest of a dense sampling, settled by Newton's method on (X(u) - point) . r'(u) = 0
    (X'(u) is parallel to r'(u)). Meant for a point on or near the curve, where the nearest is one."""
    count = _FOOT_SAMPLES_PER_PIECE * spline.pieces
    grid = spline.period * np.arange(count) / count
    frame = spline.frame(grid)
    u = float(grid[int(np.argmin(np.abs(frame.point + offset * frame.normal - point)))])
    for _ in range(_FOOT_STEPS):
        r, first, second = (complex(z[0]) for z in spline.derivatives(np.array([u])))
        speed = abs(first)
        normal = 1j * first / speed
        gap = r + offset * normal - point
        slope = (gap * first.conjugate()).real
        curve = (speed * speed * (1.0 - offset * (np.conj(first) * second).imag / speed**3)
                 + (gap * second.conjugate()).real)
        if curve == 0.0:
            break
        u -= slope / curve
    return float(np.mod(u, spline.period))
