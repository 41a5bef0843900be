"""Lines through a point with a direction, their crossings in homogeneous coordinates.

A crossing is computed relative to a local origin (the first line's point), so a mechanism
far from the frame's origin loses no accuracy. Parallel lines cross at infinity: the result
is a direction, not NaN.
"""

from __future__ import annotations

from msgspec import Struct

from kinepoly.geom.tolerances import PARALLEL_SIN
from kinepoly.geom.vec import Vec, cross, norm, sub, unit

__all__ = ["Intersection", "Line", "ParallelLinesError", "intersect"]


class ParallelLinesError(ArithmeticError):
    """Two lines that should cross in a point are parallel (they meet only at infinity)."""


class Line(Struct, frozen=True):
    """The line through ``through`` along ``direction`` (any non-zero length)."""

    through: Vec
    direction: Vec
    label: str = ""


class Intersection(Struct, frozen=True):
    """Where two lines cross: homogeneous (x, y, w) relative to ``origin``.

    ``sin_angle`` is the sine of the angle between the lines: the point's relative error is
    about 4u / |sin|.
    """

    origin: Vec
    homogeneous: tuple[float, float, float]
    sin_angle: float

    @property
    def is_finite(self) -> bool:
        return abs(self.sin_angle) > PARALLEL_SIN

    @property
    def point(self) -> Vec:
        if not self.is_finite:
            raise ParallelLinesError(f"the lines are parallel (sin of their angle {self.sin_angle:.3g})")
        x, y, w = self.homogeneous
        return (self.origin[0] + x / w, self.origin[1] + y / w)

    @property
    def direction(self) -> Vec:
        """Unit direction toward the point at infinity (meaningful when not finite)."""
        x, y, _ = self.homogeneous
        return unit((x, y))


def intersect(first: Line, second: Line) -> Intersection:
    """Cross two lines. Homogeneous lines l = (a, b, c) relative to first.through; p = l1 x l2."""
    n1, n2 = norm(first.direction), norm(second.direction)
    if n1 == 0.0 or n2 == 0.0:
        raise ParallelLinesError("a construction line has no direction (zero vector)")
    # unit directions: a direction of any size, 1e-200 or 1e200, crosses as well as any other
    d1 = (first.direction[0] / n1, first.direction[1] / n1)
    d2 = (second.direction[0] / n2, second.direction[1] / n2)
    offset = sub(second.through, first.through)
    # first line: through the local origin, normal perp(d1); second: through offset, normal perp(d2)
    a1, b1, c1 = -d1[1], d1[0], 0.0
    a2, b2 = -d2[1], d2[0]
    c2 = -(a2 * offset[0] + b2 * offset[1])
    x = b1 * c2 - c1 * b2
    y = c1 * a2 - a1 * c2
    w = a1 * b2 - b1 * a2
    sin_angle = cross(d1, d2)
    return Intersection(origin=first.through, homogeneous=(x, y, w), sin_angle=sin_angle)
