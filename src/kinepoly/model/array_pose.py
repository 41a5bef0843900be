"""Link poses over an array of inputs: world = origin + rotation * local, rotation a unit complex.

The array counterpart of ``solve.pose.LinkPose``: ``origin`` is the link frame's origin in the
frame (x + iy per row), ``rotation`` is e^(i theta) per row. theta itself is read off only when
an angle is reported.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from msgspec import Struct, field

from kinepoly.geom.arrays import DEGREES_PER_RADIAN, Points, Reals, length
from kinepoly.model.pose import LinkPose

__all__ = ["ArrayPose", "is_origin", "local_point", "pose_at", "pose_from_point", "pose_from_two_points",
           "still_pose"]


def local_point(local: tuple[float, float]) -> complex:
    """A link's own coordinates (x, y) as x + iy: one number, or one per row where a family's members differ
    (``model.family``; an array, typed as the number it stands for row by row, as ``Mechanism.local`` types it)."""
    rows = getattr(local, "rows", None)  # a family's point (model.family.RowPoint): made once
    if rows is not None:
        return rows  # type: ignore[no-any-return]
    x, y = local
    if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
        out = np.empty(np.broadcast(x, y).shape, np.complex128)
        out.real, out.imag = x, y
        return out
    return complex(x, y)


def is_origin(local: tuple[float, float]) -> bool:
    """Whether the link's own coordinates are (0, 0) for every member."""
    x, y = local
    return not isinstance(x, np.ndarray) and not isinstance(y, np.ndarray) and x == 0.0 and y == 0.0


def _member_span(local_a: tuple[float, float], local_b: tuple[float, float]) -> tuple[Points, int] | None:
    """b - a one per member where either point is a family's (``model.family.RowPoint``), with its rows per member;
    None for two points of one mechanism."""
    a, b = getattr(local_a, "members", None), getattr(local_b, "members", None)
    if a is None and b is None:
        return None
    varied: Any = local_a if a is not None else local_b
    each = int(varied.rows_each)
    first = a if a is not None else complex(local_a[0], local_a[1])
    second = b if b is not None else complex(local_b[0], local_b[1])
    return np.asarray(second - first), each


class ArrayPose(Struct, frozen=True):
    """A link's place in the frame at every row."""

    origin: Points
    rotation: Points
    still: bool = False
    """The frame itself: world = local at every row."""
    _found: dict[tuple[float, float, float, float], Points] = field(default_factory=dict)
    """``world_at`` of each point given as one number, made once (the closure that places a link and the
    polygons that read its points share it: do not change it in place)."""

    def world(self, local: tuple[float, float]) -> Points:
        return self.world_at(local_point(local))

    def world_at(self, at: complex) -> Points:
        """``world`` of a point given as x + iy (``local_point``): one number, or one per row in a family."""
        if isinstance(at, complex):
            if at == 0 and not self.still:
                return self.origin
            key = _key(at)
            found = self._found
            if key in found:
                return found[key]
            if self.still:
                out = np.empty(len(self.origin), np.complex128)
                out.fill(at)
            else:
                out = self.rotation * at
                np.add(self.origin, out, out=out)  # origin + rotation at, in place (``geom.arrays``)
            found[key] = out
            return out
        if self.still:
            return at
        return self.origin + self.rotation * at

    def made(self, at: complex) -> Points | None:
        """``world_at(at)`` of a point given as one number where it was made already, else None (nothing made)."""
        return self._found.get(_key(at))

    def to_local(self, world: Points) -> Points:
        return (world - self.origin) * self.rotation.conjugate()

    def theta(self, degrees: bool = False) -> Reals:
        """theta in radians (or degrees), in (-pi, pi] like ``Solution.angle``."""
        angle: Reals = np.arctan2(self.rotation.imag, self.rotation.real)  # np.angle's arithmetic, without its wrapper
        if degrees:
            angle *= DEGREES_PER_RADIAN  # np.degrees' factor, as the sweep's columns use it
        half = 180.0 if degrees else math.pi
        if len(angle) and np.minimum.reduce(angle) == -half:  # one reduction where none is at -half, the usual case
            angle[angle == -half] = half
        return np.asarray(angle)

    @staticmethod
    def of_rows(poses: Sequence[LinkPose]) -> ArrayPose:
        """The array pose whose row k is ``poses[k]``."""
        origin = np.array([complex(p.x, p.y) for p in poses], np.complex128)
        rotation = np.array([complex(math.cos(p.theta), math.sin(p.theta)) for p in poses], np.complex128)
        return ArrayPose(origin, rotation)

    def row(self, k: int) -> tuple[float, float, float]:
        """(x, y, theta) of row k, for the scalar solvers."""
        z, u = complex(self.origin[k]), complex(self.rotation[k])
        return (z.real, z.imag, math.atan2(u.imag, u.real))


def _key(at: complex) -> tuple[float, float, float, float]:
    """A point's key among the points made (``ArrayPose.world_at``): its coordinates and their signs (-0.0 is not
    0.0)."""
    return (at.real, at.imag, math.copysign(1.0, at.real), math.copysign(1.0, at.imag))


def still_pose(n: int) -> ArrayPose:
    """The frame (or a link fixed to it): origin 0, not turned."""
    return ArrayPose(np.zeros(n, np.complex128), np.ones(n, np.complex128), still=True)


def pose_from_point(local: tuple[float, float], world: Points, rotation: Points) -> ArrayPose:
    """The pose that puts ``local`` at ``world`` with the given rotation."""
    return pose_at(local_point(local), world, rotation)


def pose_at(at: complex, world: Points, rotation: Points) -> ArrayPose:
    """``pose_from_point`` of a point given as x + iy (``local_point``): one number, or one per row in a family."""
    if isinstance(at, complex) and at == 0:
        return ArrayPose(world, rotation)
    origin = np.asarray(rotation * at)
    return ArrayPose(np.subtract(world, origin, out=origin), rotation)  # world - rotation at, in place


def pose_from_two_points(local_a: tuple[float, float], local_b: tuple[float, float], world_a: Points,
                         world_b: Points, rigid: bool = False) -> ArrayPose:
    """The pose that puts ``local_a`` at ``world_a`` and turns a->b along world_a->world_b.

    The angle angle_of(world_b - world_a) - angle_of(local_b - local_a) of the scalar solver,
    as a rotation: the unit vector of world_a->world_b times the conjugate unit of local a->b.
    ``rigid``: the caller placed world_b at |local_b - local_a| from world_a (on a circle of
    that radius), so the span need not be measured: the rotation is span / local.
    """
    span = world_b - world_a
    members = _member_span(local_a, local_b)
    if members is not None:  # a family's link (model.family): its shape's factor per member, repeated
        shape, each = members
        factor = shape.conjugate() / (abs(shape) * abs(shape)) if rigid else (shape / abs(shape)).conjugate()
        turned = span * np.repeat(factor, each) if rigid else span * (1.0 / length(span)) * np.repeat(factor, each)
        return pose_from_point(local_a, world_a, turned)
    local = complex(local_b[0] - local_a[0], local_b[1] - local_a[1])  # two points of one mechanism: numbers
    if rigid:
        rotation = span * (local.conjugate() / (abs(local) * abs(local)))
    else:
        rotation = span * (1.0 / length(span)) * (local / abs(local)).conjugate()
    return pose_at(complex(local_a[0], local_a[1]), world_a, rotation)
