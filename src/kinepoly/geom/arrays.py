"""The 2D kernel of the sweep: the same constructions as ``kinepoly.geom``, over arrays of positions.

A point or a vector of the plane is one complex number x + iy, so an array of N complex
numbers is that point at N inputs; ``1j * v`` is v turned 90 degrees counter-clockwise (the
``perp`` of ``geom.vec``) and multiplying by a unit complex number turns a vector. The
formulas are those of ``geom.lines`` term by term: two lines cross in homogeneous coordinates
relative to the first line's point, a circle meets a circle or a line in the same closed forms,
and the same slack decides whether they meet.

The sweep runs these under ``np.errstate(all="ignore")``: a row where two lines are parallel
or a circle misses is flagged by its ``sin_angle`` or ``slack``, and whatever its values hold
is masked before anything is reported (no NaN reaches an output).

Arrays made in place: where a formula's steps make arrays that are needed only by the next step, a step may
write into one of them (``out=``, ``+=``) rather than make a new one: the same operation on the same operands
in the same order, so the same bits, with fewer new arrays per call (each costs a fresh buffer). One exception:
a complex product is never written over one of its own operands, since numpy's loop for a single row then
rounds differently from its loop for a new array (a solve is a batch of one row).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt
from msgspec import Struct

__all__ = [
    "Bools",
    "Crossing",
    "DEGREES_PER_RADIAN",
    "Points",
    "PointsLike",
    "RADIANS_PER_DEGREE",
    "Reals",
    "circle_circle",
    "circle_line",
    "cross",
    "cross_lines",
    "dot",
    "length",
    "trues",
    "turn",
]

Points = npt.NDArray[np.complex128]
"""N points (or vectors) of the plane, x + iy."""
Reals = npt.NDArray[np.float64]
Bools = npt.NDArray[np.bool_]
PointsLike = Points | complex
"""Points that may be one constant of the scene (a point of the frame, a line in a guide's frame)."""

RADIANS_PER_DEGREE = math.pi / 180.0
"""The factor of ``np.radians`` (numpy's ``deg2rad`` is x * (pi / 180)): an array multiplied by it holds
``np.radians``' values bit for bit, made by numpy's loop for products rather than a call per element."""
DEGREES_PER_RADIAN = 180.0 / math.pi
"""The factor of ``np.degrees`` (``rad2deg`` is x * (180 / pi)), as ``RADIANS_PER_DEGREE``."""


def cross(a: PointsLike, b: PointsLike) -> Reals:
    """z-component of a x b, per row: positive when b lies counter-clockwise of a."""
    return np.asarray((a.conjugate() * b).imag)


def dot(a: PointsLike, b: PointsLike) -> Reals:
    return np.asarray((a.conjugate() * b).real)


def length(a: PointsLike) -> Reals:
    return np.asarray(np.abs(a))


def trues(n: int | np.integer[Any]) -> Bools:
    """``np.ones(n, np.bool_)``: every row's mask, made by numpy's C functions (``np.ones`` is a Python function
    over them, and a sweep makes a few masks per call)."""
    out = np.empty(n, np.bool_)
    out.fill(True)
    return out


def turn(angle_rad: float) -> complex:
    """The unit complex number that turns a vector by ``angle_rad`` (a constant of the scene)."""
    return complex(np.cos(angle_rad), np.sin(angle_rad))


class Crossing(Struct, frozen=True):
    """Where two families of lines cross, row by row: through1 + along_first * direction1.

    ``sin_angle`` is the sine of the angle between the lines: the caller flags
    ``|sin_angle| <= PARALLEL_SIN`` as singular exactly as ``geom.lines.Intersection`` does, and
    masks ``point`` there. ``along_first`` (and ``along_second()``) say how far along each line,
    in units of its direction vector, the crossing lies: for a line perpendicular to a link
    AB drawn with direction k x AB, that is the link's omega (or alpha) read off the polygon,
    |v_B/A| / |AB| with its sense.
    """

    point: Points
    sin_angle: Reals
    along_first: Reals
    offset_conjugate: Points
    """The conjugate of through2 - through1 (the first line's point to the second's)."""
    direction1: PointsLike
    w: Reals

    def along_second(self) -> Reals:
        """through2 + along_second * direction2 is the same point."""
        return np.asarray((self.offset_conjugate * self.direction1).imag / self.w)  # cross(offset, direction1)


def cross_lines(through1: PointsLike, direction1: PointsLike, through2: PointsLike, direction2: PointsLike,
                length1: float | None = None, length2: float | None = None,
                product: Points | None = None, sin_angle: Reals | None = None) -> Crossing:
    """Cross line 1 (through1, direction1) with line 2, in homogeneous coordinates relative to through1.

    With the first line l1 = (-d1y, d1x, 0) through the local origin and the second
    l2 = (-d2y, d2x, c2) through the offset o = through2 - through1, c2 = -(-d2y ox + d2x oy),
    the crossing l1 x l2 is (d1x c2, d1y c2, w) with w = d1 x d2: the point through1 + d1 c2 / w.
    ``length1``, ``length2``: the directions' lengths where the caller knows them (a link's
    length, 1 for a slide), else they are measured. ``product``: conj(direction1) * direction2
    where the caller has it (its imaginary part is w); ``sin_angle``: w / (length1 length2) where the
    caller has it too (the lengths are then not needed).
    """
    offset = np.asarray(through2 - through1)
    offset_conjugate = np.conjugate(offset, out=offset)  # a new array: conjugated where it is
    crossed = np.asarray(offset_conjugate * direction2)
    c2 = crossed.imag  # cross(offset, direction2), cross(direction1, direction2)
    w = np.asarray((direction1.conjugate() * direction2 if product is None else product).imag)
    if sin_angle is None:
        norm1 = length(direction1) if length1 is None else length1
        norm2 = length(direction2) if length2 is None else length2
        sin_angle = w / (norm1 * norm2)
    along = c2 / w
    if crossed.shape == along.shape:  # direction1 along, in the array c2 was read from (not needed after)
        point = np.multiply(direction1, along, out=crossed)
    else:
        point = np.asarray(direction1 * along)
    np.add(through1, point, out=point)  # through1 + direction1 along, in place (see the module)
    return Crossing(point, sin_angle, along, offset_conjugate, direction1, w)


def circle_circle(c1: Points, r1: Reals | float, c2: Points, r2: float) -> tuple[Points, Points, Reals, Reals, Reals]:
    """The two points where two circles meet, the one left of c1->c2 first; the slack h^2. The centres are
    arrays of rows (one row or many): the steps write into the arrays they make.

    Returns (left, right, slack, d, h): slack < 0 where they do not meet (the points are then the
    foot on c1c2), d = |c1 c2|, h the half chord. Coincident centres give a slack that is not
    a number: the row does not close.
    """
    # the plain formula step by step, in place where it can (see the module: arrays made in place)
    d_vec = np.asarray(c2 - c1)
    d = length(d_vec)
    inverse = 1.0 / d
    a = d * d
    a += (r1 - r2) * (r1 + r2)
    slack = np.multiply(0.5, inverse)  # 0.5 / d, in the array that becomes the slack
    a *= slack  # (d d + (r1 - r2)(r1 + r2)) (0.5 / d)
    h = np.add(r1, a)  # r1 + a, in the array that becomes h
    np.subtract(r1, a, out=slack)
    slack *= h  # (r1 - a)(r1 + a)
    np.maximum(slack, 0.0, out=h)
    np.sqrt(h, out=h)
    a *= inverse  # a / d: real factors before the one complex product
    base = d_vec * a
    np.add(c1, base, out=base)  # the foot on c1c2
    np.multiply(h, inverse, out=inverse)  # h / d
    offset = np.asarray(1j * d_vec)
    offset *= inverse
    left = np.add(base, offset, out=d_vec)  # the foot and the offset, in c1c2's array (not needed after)
    return left, np.subtract(base, offset, out=base), slack, d, h  # the foot, a new array, made the right point


def circle_line(center: PointsLike, radius: Reals | float, through: PointsLike,
                direction: PointsLike) -> tuple[Points, Points, Reals, Reals]:
    """The two points where a circle meets a line, the one further along the direction first.

    Returns (ahead, behind, slack, half) with slack = r^2 - h^2, h the distance of the centre
    from the line; slack < 0 where they do not meet; half the half chord.
    """
    u: PointsLike = direction / length(direction)  # type: ignore[assignment]
    rel = center - through
    along = dot(u, rel)
    h = np.abs(cross(u, rel))
    foot = through + along * u
    slack = (radius - h) * (radius + h)
    half = np.sqrt(np.maximum(slack, 0.0))
    step = half * u
    return np.asarray(foot + step), np.asarray(foot - step), np.asarray(slack), np.asarray(half)
