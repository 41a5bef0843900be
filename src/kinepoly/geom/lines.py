"""Lines through a point with a direction, their crossings in homogeneous coordinates.

A crossing is computed relative to a local origin (the first line's point), so a mechanism
far from the frame's origin loses no accuracy. Parallel lines cross at infinity: the result
is a direction, not NaN.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from kinepoly.geom.tolerances import PARALLEL_SIN, UNIT_ROUNDOFF
from kinepoly.geom.vec import Vec, add, cross, dot, norm, perp, scale, sub, unit

__all__ = ["Intersection", "Line", "ParallelLinesError", "circle_circle", "circle_line", "intersect"]


class ParallelLinesError(ArithmeticError):
    """Two lines that should cross in a point are parallel (they meet only at infinity)."""


@dataclass(frozen=True)
class Line:
    """The line through ``through`` along ``direction`` (any non-zero length)."""

    through: Vec
    direction: Vec
    label: str = ""


@dataclass(frozen=True)
class Intersection:
    """Where two lines cross: homogeneous (x, y, w) relative to ``origin``.

    ``sin_angle`` is the sine of the angle between the lines; ``error_bound`` the estimated
    relative error of the point, about 4u / |sin|.
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

    @property
    def error_bound(self) -> float:
        return 4.0 * UNIT_ROUNDOFF / max(abs(self.sin_angle), 1e-300)


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


def circle_line(center: Vec, radius: float, line: Line) -> tuple[Vec, Vec, float]:
    """The two points where a circle meets a line, the one further along the direction first.

    Returns (ahead, behind, slack) with slack = r^2 - h^2 (h the distance of the center from the
    line); slack < 0 means they do not meet and the points are the foot of the perpendicular.
    """
    u = unit(line.direction)
    rel = sub(center, line.through)
    along = dot(rel, u)
    h = cross(u, rel)
    foot = add(line.through, scale(along, u))
    slack = (radius - abs(h)) * (radius + abs(h))
    half = math.sqrt(slack) if slack > 0.0 else 0.0
    return add(foot, scale(half, u)), sub(foot, scale(half, u)), slack


def circle_circle(c1: Vec, r1: float, c2: Vec, r2: float) -> tuple[Vec, Vec, float]:
    """The two points where two circles meet: the one left of c1->c2 first.

    Returns (left, right, slack), slack = h^2 (negative when they do not meet).
    """
    d_vec = sub(c2, c1)
    d = norm(d_vec)
    if d == 0.0:
        return c1, c1, -1.0
    e = scale(1.0 / d, d_vec)
    a = (d * d + (r1 - r2) * (r1 + r2)) / (2.0 * d)
    slack = (r1 - a) * (r1 + a)
    h = math.sqrt(slack) if slack > 0.0 else 0.0
    base = add(c1, scale(a, e))
    return add(base, scale(h, perp(e))), sub(base, scale(h, perp(e))), slack
