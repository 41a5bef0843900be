"""Points and lines of the projective plane: a point at infinity is an ordinary value.

A point is a triple (x, y, w): the point (x/w, y/w), or for w = 0 the point at infinity in the
direction (x, y). A line is a triple (a, b, c), the points with a x + b y + c w = 0; (0, 0, 1) is
the line at infinity. The line through two points is their cross product, and so is the point
where two lines cross: one formula (``wedge``) for both, with no special case for infinity.

Accuracy. The products are taken in a ``LocalFrame``: coordinates relative to an origin near the
figure and divided by its size, so a figure far from the world's origin loses nothing. Every
value is a unit 3-vector with an error estimate, the angle (radians on the unit sphere) by which
it may be off. For unit p and q, |p x q| is the sine of their angle; the product is off by about
(e_p + e_q + 4u) / |p x q|. That sine is the conditioning of the join or the crossing: near 1 when
the two points are far apart (the lines cross at a good angle, or are parallel but apart), near 0
when they coincide. Below ``COINCIDENT_SIN`` (or below their own errors) they are one point (one
line) and the product is no value: ``Wedge.value`` is None.
"""

from __future__ import annotations

import math

from msgspec import Struct

from kinepoly.geom.tolerances import COINCIDENT_SIN, PARALLEL_SIN, UNIT_ROUNDOFF
from kinepoly.geom.vec import Vec

__all__ = ["LocalFrame", "Place", "Projective", "Triple", "Wedge", "canonical_direction", "wedge"]

Triple = tuple[float, float, float]

_ROUNDING = 4.0 * UNIT_ROUNDOFF
"""Error of a unit vector made from exact data, and added by one cross product."""


class Projective(Struct, frozen=True):
    """A point or a line of a ``LocalFrame``: a unit 3-vector and its error (radians on the sphere)."""

    vector: Triple
    error: float


class Wedge(Struct, frozen=True):
    """p x q: the line through two points, or the point where two lines cross.

    ``sin`` is |p x q| for the unit inputs, the sine of their angle: the step's conditioning.
    ``value`` is None when p and q are one point (one line), so that no single result exists.
    """

    value: Projective | None
    sin: float


def _unit(v: Triple) -> tuple[Triple, float]:
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if n == 0.0:
        return (0.0, 0.0, 0.0), 0.0
    return (v[0] / n, v[1] / n, v[2] / n), n


def wedge(p: Projective, q: Projective) -> Wedge:
    """The cross product of two unit 3-vectors, with its conditioning and error."""
    (a1, b1, c1), (a2, b2, c2) = p.vector, q.vector
    raw = (b1 * c2 - c1 * b2, c1 * a2 - a1 * c2, a1 * b2 - b1 * a2)
    vector, sin = _unit(raw)
    if sin <= max(COINCIDENT_SIN, p.error + q.error):
        return Wedge(None, sin)
    return Wedge(Projective(vector, (p.error + q.error + _ROUNDING) / sin), sin)


def canonical_direction(direction: Vec) -> Vec:
    """The unit vector of a point at infinity, its sign chosen so its angle is in [-45, 135) degrees."""
    x, y = direction
    n = math.hypot(x, y)
    if n == 0.0:
        raise ZeroDivisionError("the zero vector is no direction")
    x, y = x / n, y / n
    if x + y < 0.0 or (x + y == 0.0 and x < 0.0):
        x, y = -x, -y
    return (x + 0.0, y + 0.0)  # no -0.0


class Place(Struct, frozen=True):
    """Where a projective point lies in the world: a position, or a direction at infinity.

    ``relative_error`` is the estimated error of the position over its distance from the
    frame's origin (at least the frame's size), or of the direction in radians.
    """

    position: Vec | None
    direction: Vec | None
    relative_error: float

    @property
    def is_at_infinity(self) -> bool:
        return self.position is None

    @property
    def homogeneous(self) -> Triple:
        """(x, y, 1) for a position, (ux, uy, 0) for a direction."""
        if self.position is not None:
            return (self.position[0], self.position[1], 1.0)
        assert self.direction is not None
        return (self.direction[0], self.direction[1], 0.0)


class LocalFrame(Struct, frozen=True):
    """Coordinates relative to ``origin`` and divided by ``size``.

    Points come in as the caller's coordinates; ``offset`` is added to every position placed
    back, once (a solve that runs near its own origin reports in the user's frame).
    """

    origin: Vec
    size: float
    offset: Vec = (0.0, 0.0)

    def point(self, at: Vec, error: float = _ROUNDING) -> Projective:
        """The finite world point ``at``."""
        vector, _ = _unit(((at[0] - self.origin[0]) / self.size, (at[1] - self.origin[1]) / self.size, 1.0))
        return Projective(vector, error)

    def point_at_infinity(self, direction: Vec, error: float = _ROUNDING) -> Projective:
        """The point at infinity in the world direction ``direction`` (either sense)."""
        vector, n = _unit((direction[0], direction[1], 0.0))
        if n == 0.0:
            raise ZeroDivisionError("a point at infinity needs a direction, got the zero vector")
        return Projective(vector, error)

    def place(self, p: Projective) -> Place:
        """The world position of p, or its direction when p is at infinity (within its error)."""
        x, y, w = p.vector
        planar = math.hypot(x, y)
        if abs(w) <= max(PARALLEL_SIN, p.error) * planar:
            return Place(None, canonical_direction((x, y)), p.error)
        r = planar / abs(w)
        position = (self.offset[0] + (self.origin[0] + self.size * x / w),
                    self.offset[1] + (self.origin[1] + self.size * y / w))
        return Place(position, None, p.error * (1.0 + r * r) / max(1.0, r))

    def line(self, line: Projective) -> tuple[Vec, Vec] | None:
        """A world line as (a point on it, its unit direction); None for the line at infinity."""
        a, b, c = line.vector
        n = math.hypot(a, b)
        if n <= max(PARALLEL_SIN, line.error) * abs(c):
            return None
        foot = (-c * a / (n * n), -c * b / (n * n))
        through = (self.offset[0] + (self.origin[0] + self.size * foot[0]),
                   self.offset[1] + (self.origin[1] + self.size * foot[1]))
        return through, (-b / n, a / n)
