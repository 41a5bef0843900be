"""A velocity or acceleration polygon under construction over rows: the array twin of ``construct.builder``.

Tips are complex arrays (one per row), pole at 0. Points of an already-known link get their tips
lazily, in the same order and by the same rules as the scalar builder:
- a point of the frame is the pole;
- with two tips known on the link, by Mehmke's image: the lines from the two known tips at the
  angles of the link's triangle are crossed (a flat triangle by proportional division; tips that
  coincide give the same tip). The angles are the link's own, so the crossing for a unit side is
  found once per point (``_similar``) and scaled by the polygon side at every row;
- with one tip and the link's rate known, by laying the relative vector.
The crossings of direction lines are recorded with their sines, so that singular and
near-singular rows can be flagged as ``PolygonBuilder.cross_lines`` flags them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from kinepoly.errors import SingularityError
from kinepoly.geom import Line as GeomLine
from kinepoly.geom import intersect as geom_intersect
from kinepoly.geom.tolerances import COLLINEAR_SIN
from kinepoly.model.mechanism import Mechanism, point_label
from kinepoly.geom.arrays import Crossing, Points, PointsLike, Reals, cross, cross_lines
from kinepoly.sweep.position import SweepPositions

__all__ = ["ArrayPolygon", "JointSolve", "Line", "LineCrossing"]

Kind = Literal["velocity", "acceleration"]
Line = tuple[Points, PointsLike, float | None]
"""A direction line: through, direction, and the direction's length where it is a constant of the scene."""


@dataclass(frozen=True)
class LineCrossing:
    """Two direction lines crossed at every row: the group, the tip found, the sine of their angle,
    and how far along the first line they cross (every later value of the polygon is a sum of
    products of these, so where it is finite, they are)."""

    kind: Kind
    group: str
    what: str
    sin_angle: Reals
    along: Reals


@dataclass(frozen=True)
class JointSolve:
    """A group's joint equations solved at every row (no two lines): the condition number of each row."""

    kind: Kind
    group: str
    condition: Reals


@dataclass(frozen=True)
class _Member:
    label: str
    at: Points
    fixed: bool


class ArrayPolygon:
    """Mutable while one polygon is constructed over all rows; ``tips``, ``rate`` and ``crossings`` are its output."""

    def __init__(self, mechanism: Mechanism, positions: SweepPositions, kind: Kind,
                 omega: dict[str, Reals] | None = None) -> None:
        self.mechanism = mechanism
        self.positions = positions
        self.kind = kind
        self.n = len(positions.ok)
        self.zero = np.zeros(self.n, np.complex128)
        self.omega = omega if omega is not None else {}
        self.rate: dict[str, Reals] = {}
        self.tips: dict[str, Points] = {}
        self.members: dict[str, list[_Member]] = {}
        self.crossings: list[LineCrossing | JointSolve] = []
        self.names = positions.names
        assert self.names is not None
        if mechanism.ground is not None:
            self.rate[mechanism.ground] = np.zeros(self.n)
            for p in mechanism.scene.link(mechanism.ground).points:
                self._register(p.name, self.zero, p.name, list(self.names.links_of[p.name]))

    # -- where points are -----------------------------------------------------------------------
    def world(self, point: str) -> Points:
        return self.positions.point(point)

    def label(self, link: str, point: str) -> str:
        assert self.names is not None
        return point if self.names.has_point(link, point) else point_label(point, link)

    # -- rates ------------------------------------------------------------------------------------
    def rate_of(self, link: str) -> Reals | None:
        return self.mechanism.class_rate(self.rate, link)

    def set_rate(self, link: str, value: Reals) -> None:
        for other in self.mechanism.turning_together(link):
            self.rate[other] = value

    def omega_of(self, link: str) -> Reals:
        omega = self.mechanism.class_rate(self.omega, link)
        return np.zeros(self.n) if omega is None else omega

    # -- tips -------------------------------------------------------------------------------------
    def _register(self, label: str, value: Points, point: str, links: list[str]) -> None:
        self.tips[label] = value
        assert self.names is not None
        at = self.world(point)
        for link in links:
            entries = self.members.setdefault(link, [])
            if all(m.label != label for m in entries):
                entries.append(_Member(label, at, point in self.names.points_of[link]))

    def add_tip(self, link: str, point: str, value: Points) -> str:
        label = self.label(link, point)
        assert self.names is not None
        links = list(self.names.links_of[point]) if label == point else [link]
        self._register(label, value, point, links)
        return label

    def tip(self, link: str, point: str) -> Points:
        """The tip of ``point`` as a point of ``link``, constructing it when it is not known yet."""
        label = self.label(link, point)
        if label in self.tips:
            return self.tips[label]
        if link == self.mechanism.ground:
            self.add_tip(link, point, self.zero)
            return self.zero
        members = self.members.get(link, [])
        if len(members) >= 2:
            value = self._image(link, point, label, members)
        elif len(members) == 1 and self.rate_of(link) is not None:
            value = self._relative(link, point, members[0])
        else:
            raise SingularityError(f"the {self.kind} of {label} cannot be constructed: link {link} has "
                                   f"{len(members)} known tip(s) and no known angular rate")
        self.add_tip(link, point, value)
        return value

    def _relative(self, link: str, point: str, member: _Member) -> Points:
        r = self.world(point) - member.at
        start = self.tips[member.label]
        rate = self.rate_of(link)
        assert rate is not None
        if self.kind == "velocity":
            return np.asarray(start + rate * (1j * r))
        w = self.omega_of(link)
        return np.asarray(start - (w * w) * r + rate * (1j * r))

    def _image(self, link: str, point: str, label: str, members: list[_Member]) -> Points:
        assert self.names is not None
        at = self.world(point)
        pairs = [(m, k) for i, m in enumerate(members) for k in members[i + 1:]]
        if point in self.names.points_of[link] and all(m.fixed for m in members):
            local = {m.label: self._local(link, m.label) for m in members}
            here = self._local(link, label)
            first, second = max(pairs, key=lambda pair: _key(local[pair[0].label], local[pair[1].label], here))
            a, b = self.tips[first.label], self.tips[second.label]
            return np.asarray(a + (b - a) * _similar(local[first.label], local[second.label], here, label, link))
        keys = np.stack([np.asarray(_key(m.at, k.at, at)) for m, k in pairs])
        best = np.argmax(keys, axis=0)
        value = self.zero
        for index, (m, k) in enumerate(pairs):
            if np.any(best == index):
                image = self._image_of(m, k, at, label, link)
                value = image if len(pairs) == 1 else np.where(best == index, image, value)
        return value

    def _local(self, link: str, label: str) -> complex:
        point = label.partition("@")[0]
        x, y = self.mechanism.local(link, point)
        return complex(x, y)

    def _image_of(self, first: _Member, second: _Member, at: Points, label: str, link: str) -> Points:
        """Mehmke, row by row (a triangle whose corner slides on the link changes from row to row)."""
        wa, wb = first.at, second.at
        side = wb - wa
        a, b = self.tips[first.label], self.tips[second.label]
        polygon_side = b - a
        ratio_a = (at - wa) / side
        ratio_b = (at - wb) / (wa - wb)
        turn_a, turn_b = ratio_a / np.abs(ratio_a), ratio_b / np.abs(ratio_b)
        flat_value = a + polygon_side * ratio_a  # proportional division: the foot, then the height
        sin_lines = np.abs(np.sin(np.angle(turn_b) - np.angle(turn_a)))
        crossing = cross_lines(a, polygon_side * turn_a, b, -polygon_side * turn_b).point
        value = np.where(sin_lines >= COLLINEAR_SIN, crossing, flat_value)
        return np.asarray(np.where(polygon_side == 0.0, a, value))

    # -- the crossing of two direction lines --------------------------------------------------------
    def cross_lines(self, first: Line, second: Line, what: str, group: str) -> Crossing:
        """Cross two direction lines (through, direction, the direction's length if known) and record how well."""
        crossing = cross_lines(first[0], first[1], second[0], second[1], first[2], second[2])
        self.crossings.append(LineCrossing(self.kind, group, what, crossing.sin_angle, crossing.along_first))
        return crossing


def _similar(wa: complex, wb: complex, at: complex, label: str, link: str) -> complex:
    """Where Mehmke's two lines cross for a polygon side of 1 from a to b: the image is a + (b - a) k.

    The line from a at the triangle's angle at A and the line from b at its angle at B are
    crossed (in homogeneous coordinates, as ``geom.intersect``) for a = 0, b = 1; the image of a
    link is similar to it, so for any a and b they cross at a + (b - a) k. A flat triangle (lines
    at a sine below ``COLLINEAR_SIN``) takes k from proportional division instead: the foot's
    ratio along AB and the height over |AB|, as the scalar builder does.
    """
    side = wb - wa
    if side == 0:
        raise SingularityError(f"image of {label}: two known points of link {link} coincide")
    ratio = (at - wa) / side
    turn_a = ratio / abs(ratio) if ratio != 0 else 1.0 + 0j
    ratio_b = (at - wb) / (wa - wb)
    turn_b = ratio_b / abs(ratio_b) if ratio_b != 0 else 1.0 + 0j
    crossing = geom_intersect(GeomLine((0.0, 0.0), (turn_a.real, turn_a.imag)),
                              GeomLine((1.0, 0.0), (-turn_b.real, -turn_b.imag)))
    if abs(crossing.sin_angle) < COLLINEAR_SIN or not crossing.is_finite:
        return ratio
    x, y = crossing.point
    return complex(x, y)


def _key(wa: PointsLike, wb: PointsLike, at: PointsLike) -> Reals | float:
    """The scalar builder's choice of the two known tips: |ab| + |ab x a->point|."""
    side = wb - wa
    return np.abs(side) + np.abs(cross(side, at - wa))
