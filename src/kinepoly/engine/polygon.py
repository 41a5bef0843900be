"""A velocity or acceleration polygon under construction over rows, and its steps recorded on demand.

Tips are complex arrays (one value per row), pole at 0. Points of an already-known link get
their tips lazily, when a later step needs them:

- a point of the frame is the pole;
- with two tips known on the link, by Mehmke's image: the lines from the two known tips at the
  angles of the link's triangle are crossed (a flat triangle by proportional division of the
  known side; tips that coincide give the same tip);
- with one tip and the link's rate known, by laying the relative vector.

Every crossing of two direction lines is kept with the sine of their angle, so that a sweep can
mark singular and near-singular rows; a *strict* polygon (a solve) raises ``SingularityError``
at a parallel pair instead. With ``record`` the polygon records the steps of row 0 as data
(``engine.steps``): a sweep records nothing.
"""

from __future__ import annotations

import cmath
import functools
import math
from collections.abc import Callable
from typing import Literal, NamedTuple

import numpy as np
from msgspec import Struct

from kinepoly.engine.groups import PlanConstants
from kinepoly.engine.inputs import describe_input
from kinepoly.engine.placement import Positions
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.errors import SingularityError
from kinepoly.geom.arrays import Crossing, Points, PointsLike, Reals, cross, cross_lines
from kinepoly.geom.lines import Line as StepLine
from kinepoly.geom.tolerances import COLLINEAR_SIN, PARALLEL_SIN
from kinepoly.geom.vec import magnitude, phase
from kinepoly.model.array_pose import local_point
from kinepoly.model.family import FamilyMechanism
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.link_point import LinkPoint, point_of

__all__ = ["CrossLines", "JointSolve", "Line", "LineCrossing", "Polygon", "sense"]

Kind = Literal["velocity", "acceleration"]
Line = tuple[Points, PointsLike, float | None]
"""A direction line: through, direction, and the direction's length where it is a constant of the scene."""
CrossLines = Callable[[PointsLike, PointsLike, PointsLike, PointsLike, float | None, float | None], Crossing]
"""How two families of direction lines are crossed: ``geom.arrays.cross_lines`` (the bench swaps in others)."""
Vec = tuple[float, float]


def sense(rate: float) -> str:
    return "ccw" if rate > 0 else ("cw" if rate < 0 else "zero")


class LineCrossing(Struct, frozen=True):
    """Two direction lines crossed at every row: the group, the tip found, the sine of their angle,
    and how far along the first line they cross (every later value of the polygon is a sum of
    products of these, so where it is finite, they are)."""

    kind: Kind
    group: str
    what: str
    sin_angle: Reals
    along: Reals


class JointSolve(Struct, frozen=True):
    """A group's joint equations solved at every row (no two lines): the condition number of each row."""

    kind: Kind
    group: str
    condition: Reals


_IMAGE_MEMBERS = 8
"""An image is built from two of its link's first 8 known tips (the best pair of them): each tip found joins
the link's known ones, so that choosing among all would cost the n-th point of a link n² pairs (200 points on
one link: 60 s). No example has a link with more than 8 known tips where an image is built."""

class Member(NamedTuple):
    """A known tip of a link: its label, the point (where it is at every row: ``Positions.point``), whether it is
    fixed on the link (a constant of the plan, made once: ``PlanConstants.tips``)."""

    label: str
    point: str
    fixed: bool


class Polygon:
    """Mutable while one polygon is constructed over all rows; ``tips``, ``rate``, ``crossings`` and
    ``steps`` are its output."""

    def __init__(self, positions: Positions, kind: Kind, omega: dict[str, Reals] | None = None, *,
                 unit: str = "mm", record: bool = False, strict: bool = False,
                 crossing: CrossLines = cross_lines, constants: PlanConstants | None = None) -> None:
        self.mechanism: Mechanism = positions.mechanism
        if constants is None or (constants.mechanism is not None and constants.mechanism is not self.mechanism):
            constants = PlanConstants()
        if constants.mechanism is None:
            constants.mechanism = self.mechanism
        self.constants = constants
        """The plan's constants of construction (``PlanConstants``): read where found, else found and kept."""
        self.positions = positions
        self.kind = kind
        self.symbol = "v" if kind == "velocity" else "a"
        self.unit = f"{unit}/s" if kind == "velocity" else f"{unit}/s^2"
        self.n = positions.n
        self.zero, zero_rate = positions.zeros()  # the velocity and acceleration polygons' alike (not changed)
        self.omega = omega if omega is not None else {}
        self.normal_sign = -1.0
        """-1: a normal term points from the point toward the center (``Rules.normal`` may switch it)."""
        self.rate: dict[str, Reals] = {}
        self.tips: dict[str, Points] = {}
        self.members: dict[str, list[Member]] = {}
        self.crossings: list[LineCrossing | JointSolve] = []
        self.record = record
        self.strict = strict
        self.crossing = crossing
        self.steps: list[Step] = []
        mech = self.mechanism
        ground = self.ground = mech.ground
        """The frame (``Mechanism.ground``)."""
        self._labels = self.constants.labels
        self._together = self.constants.together
        if not self._together:
            self._together.update((link, mech.turning_together(link)) for link in mech.link_names)
        if ground is not None:
            self.set_rate(ground, zero_rate)  # and every link that slides on it without turning
            frame = self.constants.frame
            if frame is None:
                frame = self.constants.frame = tuple(self._entries(ground, p.name)
                                                     for p in mech.scene.link(ground).points)
            for label, entries in frame:
                self._register(label, self.zero, entries)

    # -- row 0 as plain values, for the steps -------------------------------------------------------
    @staticmethod
    def vec(z: PointsLike) -> Vec:
        c = complex(z if isinstance(z, complex) else z[0])
        return (c.real, c.imag)

    @staticmethod
    def num(x: Reals) -> float:
        return float(x[0])

    def step(self, step: Step) -> None:
        self.steps.append(step)

    # -- where points are ---------------------------------------------------------------------------
    def world(self, point: str) -> Points:
        return self.positions.point(point)

    def label(self, link: str, point: str) -> str:
        key = (link, point)
        labels = self._labels
        if key in labels:
            return labels[key]
        found = labels[key] = point if self.mechanism.has_point(link, point) else LinkPoint(point, link).text
        return found

    @staticmethod
    def tip_name(label: str) -> str:
        return label.lower()

    def ground_name(self) -> str:
        return self.mechanism.ground or ""

    # -- rates (omega or alpha) ---------------------------------------------------------------------
    def rate_of(self, link: str) -> Reals | None:
        rate = self.rate
        return rate[link] if link in rate else self.mechanism.class_rate(rate, link)

    def set_rate(self, link: str, value: Reals) -> None:
        rate = self.rate
        for other in self._together[link]:
            rate[other] = value

    def omega_of(self, link: str) -> Reals:
        known = self.omega
        omega = known[link] if link in known else self.mechanism.class_rate(known, link)
        return np.zeros(self.n) if omega is None else omega

    # -- tips -----------------------------------------------------------------------------------------
    def _entries(self, link: str, point: str) -> tuple[str, tuple[tuple[str, Member], ...]]:
        """The label of ``point`` as a point of ``link`` and the links whose member it becomes, each with its
        member: a named point is a point of each link that has it, fixed on it; a point of one link under
        another's (``B@4``) a member of ``link`` alone, not fixed on it."""
        label = self.label(link, point)
        if label == point:
            return label, tuple((other, Member(label, point, True)) for other in self.mechanism.links_of_point(point))
        return label, ((link, Member(label, point, False)),)

    def _register(self, label: str, value: Points, entries: tuple[tuple[str, Member], ...]) -> None:
        """Record the tip ``value`` of ``label``, a member of each link of ``entries`` (``_entries``)."""
        tips, members = self.tips, self.members
        known = label in tips  # only a label with a tip already can be a member already
        tips[label] = value
        for link, member in entries:
            of_link = members.get(link)
            if of_link is None:
                members[link] = [member]
            elif not known or all(m.label != label for m in of_link):
                of_link.append(member)

    def add_tip(self, link: str, point: str, value: Points) -> str:
        """Record the tip of ``point`` as a point of ``link`` (and of the pin's other links)."""
        key = (link, point)
        known = self.constants.tips
        found = known[key] if key in known else known.setdefault(key, self._entries(link, point))
        self._register(found[0], value, found[1])
        return found[0]

    def add_virtual_tip(self, link: str, name: str, value: Points) -> None:
        """The tip of a point the construction found on ``link`` (not a named point: a triad's Assur point,
        whose place the positions were told)."""
        self._register(name, value, ((link, Member(name, name, self.mechanism.has_point(link, name))),))

    def at(self, member: Member) -> Points:
        """Where a member's point is at every row."""
        return self.positions.point(member.point)

    def tip(self, link: str, point: str) -> Points:
        """The tip of ``point`` as a point of ``link``, constructing it when it is not known yet."""
        label = self._labels.get((link, point)) or self.label(link, point)
        known = self.tips.get(label)
        if known is not None:
            return known
        if link == self.ground:
            self.add_tip(link, point, self.zero)
            return self.zero
        members = self.members.get(link, [])
        if len(members) >= 2:
            value = self._image(link, point, label, members)
        elif len(members) == 1 and self.rate_of(link) is not None:
            value = self._relative(link, point, label, members[0])
        else:
            raise SingularityError(f"the {self.kind} of {label} cannot be constructed: link {link} has "
                                   f"{len(members)} known tip(s) and no known angular rate")
        self.add_tip(link, point, value)
        return value

    def _relative(self, link: str, point: str, label: str, member: Member) -> Points:
        r, turned = self.positions.chord(member.point, point)
        start = self.tips[member.label]
        rate = self.rate_of(link)
        assert rate is not None
        if self.kind == "velocity":
            end: Points = rate * turned
            np.add(start, end, out=end)  # start + rate turned, in place (``geom.arrays``: arrays made in place)
            if self.record:
                self._record_relative_velocity(link, label, member.label, r, start, end, rate)
            return end
        w = self.omega_of(link)
        normal = np.asarray((w * w) * r)
        middle: Points = np.subtract(start, normal, out=normal) if self.normal_sign < 0.0 else np.add(
            start, normal, out=normal)  # start -+ normal, in place
        end = rate * turned
        np.add(middle, end, out=end)  # middle + rate turned, in place
        if self.record:
            self._record_relative_acceleration(link, label, member.label, r, start, middle, end, w, rate)
        return end

    def _record_relative_velocity(self, link: str, label: str, ref: str, r: Points, start: Points, end: Points,
                                  rate: Reals) -> None:
        name = f"{label}/{ref}"
        w, length = self.num(rate), magnitude(complex(r[0]))
        size = magnitude(complex(end[0]) - complex(start[0]))
        self.step(Step(polygon="velocity", kind="known", equation=f"v_{label} = v_{ref} + v_{name}",
                       result=self.tip_name(label),
                       known=((f"v_{ref}", "magnitude and direction"), (f"v_{name}", "magnitude and direction")),
                       vectors=(DrawnVector(f"v_{name}", self.vec(start), self.vec(end), "relative"),),
                       value=self.vec(end), topic="relative",
                       params=(("point", label), ("reference", ref), ("link", link), ("ground", self.ground_name()),
                               ("length", length), ("magnitude", size), ("rate", abs(w)), ("sense", sense(w)))))

    def _record_relative_acceleration(self, link: str, label: str, ref: str, r: Points, start: Points,
                                      middle: Points, end: Points, omega: Reals, rate: Reals) -> None:
        name = f"{label}/{ref}"
        w, alpha, length = self.num(omega), self.num(rate), magnitude(complex(r[0]))
        a, m, e = complex(start[0]), complex(middle[0]), complex(end[0])
        self.step(Step(polygon="acceleration", kind="known", equation=f"a_{label} = a_{ref} + a_{name}",
                       result=self.tip_name(label),
                       known=((f"a_{ref}", "magnitude and direction"), (f"a^n_{name}", "magnitude and direction"),
                              (f"a^t_{name}", "magnitude and direction")),
                       vectors=(DrawnVector(f"a^n_{name}", self.vec(start), self.vec(middle), "normal"),
                                DrawnVector(f"a^t_{name}", self.vec(middle), self.vec(end), "tangential")),
                       value=self.vec(end), topic="relative",
                       params=(("point", label), ("reference", ref), ("link", link), ("ground", self.ground_name()),
                               ("length", length), ("magnitude", magnitude(e - a)), ("rate", abs(alpha)),
                               ("sense", sense(alpha)), ("omega", abs(w)), ("normal", magnitude(m - a)),
                               ("tangential", magnitude(e - m)))))

    # -- Mehmke's image ---------------------------------------------------------------------------------
    def _image(self, link: str, point: str, label: str, members: list[Member]) -> Points:
        key = (link, label, tuple(members))
        images = self.constants.images
        if key in images:
            rigid = images[key]
        else:
            rigid = images[key] = self._rigid_image(link, point, label, members)
        if rigid is not None:
            first_label, second_label, factor = rigid
            a, b = self.tips[first_label], self.tips[second_label]
            value = np.asarray((b - a) * factor)
            np.add(a, value, out=value)  # a + (b - a) factor, in place
            if self.record:
                first, second = (next(m for m in members if m.label == name) for name in (first_label, second_label))
        else:
            at = self.world(point)
            known = members[:_IMAGE_MEMBERS]
            pairs = [(m, k) for i, m in enumerate(known) for k in known[i + 1:]]
            if len(pairs) == 1 and self.n:  # every row builds the image from the one pair
                first, second = pairs[0]
                value = self._image_of(first, second, at)
            else:
                keys = np.stack([np.asarray(_key(self.at(m), self.at(k), at)) for m, k in pairs])
                best = keys.argmax(axis=0)
                value = self.zero
                for index, (m, k) in enumerate(pairs):
                    if (best == index).any():
                        image = self._image_of(m, k, at)
                        value = image if len(pairs) == 1 else np.where(best == index, image, value)
                first, second = pairs[int(best[0])]
        if self.record:
            self._record_image(link, label, first, second, self.world(point), value)
        return value

    def _rigid_image(self, link: str, point: str, label: str, members: list[Member]) -> tuple[str, str, complex] | None:
        """The image of a point of ``link`` whose known tips are all of points fixed on it: the labels of the two
        known tips it is built from and Mehmke's factor (``_similar``), which depend on the link's shape alone; None
        where the image is built row by row."""
        if not (self.mechanism.has_point(link, point) and all(m.fixed for m in members)):
            return None
        known = members[:_IMAGE_MEMBERS]
        pairs = [(m, k) for i, m in enumerate(known) for k in known[i + 1:]]
        local = {m.label: self._local(link, m.label) for m in members}
        here = self._local(link, label)
        if not (isinstance(here, complex) and all(isinstance(c, complex) for c in local.values())):
            return self._family_image(link, label, members, pairs)
        first, second = pairs[0] if len(pairs) == 1 else max(
            pairs, key=lambda pair: _key(local[pair[0].label], local[pair[1].label], here))
        return first.label, second.label, _similar(local[first.label], local[second.label], here, label, link)

    def _family_image(self, link: str, label: str, members: list[Member],
                      pairs: list[tuple[Member, Member]]) -> tuple[str, str, complex] | None:
        """``_rigid_image`` of a family's link whose points differ between the members (``model.family``): the
        factor member by member (the link's shape is the member's), repeated over its rows; None (row by row) where
        the members would build the image from different pairs of tips."""
        mechanism = self.mechanism
        assert isinstance(mechanism, FamilyMechanism)
        local = {m.label: mechanism.member_local(link, point_of(m.label)) for m in members}
        here = mechanism.member_local(link, point_of(label))
        chosen: tuple[Member, Member] | None = None
        factors = []
        for k in range(len(here)):
            at = complex(here[k])
            pair = pairs[0] if len(pairs) == 1 else max(
                pairs, key=lambda p: _key(complex(local[p[0].label][k]), complex(local[p[1].label][k]), at))
            if chosen is not None and pair != chosen:
                return None
            chosen = pair
            factors.append(_similar(complex(local[pair[0].label][k]), complex(local[pair[1].label][k]), at, label,
                                    link))
        assert chosen is not None
        factor = np.repeat(np.array(factors, np.complex128), mechanism.rows_each)
        return chosen[0].label, chosen[1].label, factor  # type: ignore[return-value]  # per row in a family

    def _local(self, link: str, label: str) -> complex:
        return local_point(self.mechanism.local(link, point_of(label)))

    def _image_of(self, first: Member, second: Member, at: Points) -> Points:
        """Mehmke, row by row (a triangle whose corner slides on the link changes from row to row)."""
        wa, wb = self.at(first), self.at(second)
        side = wb - wa
        a, b = self.tips[first.label], self.tips[second.label]
        polygon_side = b - a
        ratio_a = (at - wa) / side
        ratio_b = (at - wb) / (wa - wb)
        # np.angle(z) is np.arctan2(z.imag, z.real): its arithmetic, without its wrapper
        turn_a = np.exp(1j * np.arctan2(ratio_a.imag, ratio_a.real))
        turn_b = np.exp(1j * np.arctan2(ratio_b.imag, ratio_b.real))
        flat_value = a + polygon_side * ratio_a  # proportional division: the foot, then the height
        sin_lines = np.abs(np.sin(np.arctan2(turn_b.imag, turn_b.real) - np.arctan2(turn_a.imag, turn_a.real)))
        crossing = self.crossing(a, polygon_side * turn_a, b, -polygon_side * turn_b, None, None).point
        value = np.where(sin_lines >= COLLINEAR_SIN, crossing, flat_value)
        return np.asarray(np.where(polygon_side == 0.0, a, value))

    def _record_image(self, link: str, label: str, first: Member, second: Member, at_rows: Points,
                      value: Points) -> None:
        la, lb = first.label, second.label
        wa, wb, at = complex(self.at(first)[0]), complex(self.at(second)[0]), complex(at_rows[0])
        a, b = complex(self.tips[la][0]), complex(self.tips[lb][0])
        side, polygon_side = wb - wa, b - a
        if side == 0:
            raise SingularityError(f"image of {label}: the known points {la} and {lb} of link {link} coincide")
        equation = f"triangle {la.lower()}{lb.lower()}{label.lower()} ~ triangle {la}{lb}{label} (same sense)"
        common = (("link", link), ("point", label), ("first", la), ("second", lb))
        if polygon_side == 0:
            self.step(Step(polygon=self.kind, kind="image", equation=equation, result=self.tip_name(label),
                           value=self.vec(value), topic="image-translating", params=common))
            return
        angle_a = phase(at - wa) - phase(side)
        angle_b = phase(at - wb) - phase(-side)
        line_a = StepLine(self.vec(a), self.vec(polygon_side * cmath.exp(1j * angle_a)),
                          f"from {la.lower()} at angle {lb}{la}{label}")
        line_b = StepLine(self.vec(b), self.vec(-polygon_side * cmath.exp(1j * angle_b)),
                          f"from {lb.lower()} at angle {la}{lb}{label}")
        if abs(math.sin(angle_b - angle_a)) >= COLLINEAR_SIN:
            first_deg = math.degrees(math.remainder(angle_a, 2.0 * math.pi))
            second_deg = math.degrees(math.remainder(angle_b, 2.0 * math.pi))
            self.step(Step(polygon=self.kind, kind="image", equation=equation, result=self.tip_name(label),
                           lines=(line_a, line_b), value=self.vec(value), topic="image",
                           params=(*common, ("angle_first", first_deg), ("angle_second", second_deg)),
                           directions=(Direction("", "at-angle", f"{la}{lb}".lower(), la.lower(), angle_deg=first_deg),
                                       Direction("", "at-angle", f"{lb}{la}".lower(), lb.lower(),
                                                 angle_deg=second_deg))))
            return
        ratio = ((at - wa) / side).real
        height = ((at - wa) / side).imag
        self.step(Step(polygon=self.kind, kind="proportional", equation=equation, result=self.tip_name(label),
                       lines=(StepLine(self.vec(a), self.vec(polygon_side), f"{la.lower()}{lb.lower()}"),),
                       value=self.vec(value), topic="proportional",
                       params=(*common, ("ratio", ratio), ("height", height)),
                       directions=(Direction("", "along", f"{la}{lb}".lower(), la.lower()),)))

    # -- the crossing of two direction lines -------------------------------------------------------------
    def cross_lines(self, first: Line, second: Line, what: str, group: str,
                    labels: tuple[str, str] = ("", "")) -> Crossing:
        """Cross two direction lines (through, direction, the direction's length if known) and keep
        how well they cross; a strict polygon raises ``SingularityError`` where they are parallel."""
        d1, d2 = first[1], second[1]
        if self.crossing is cross_lines and not isinstance(d1, complex) and not isinstance(d2, complex):
            # lines square to two chords: their product and sine are made once for both polygons
            # (``Positions.chord_product``, ``Positions.chord_sine``)
            positions = self.positions
            product = positions.chord_product(d1, d2)
            crossing = cross_lines(first[0], d1, second[0], d2, first[2], second[2], product,
                                   positions.chord_sine(product, first[2], second[2]))
        else:
            crossing = self.crossing(first[0], first[1], second[0], second[1], first[2], second[2])
        self.crossings.append(LineCrossing(self.kind, group, what, crossing.sin_angle, crossing.along_first))
        if self.strict and not abs(float(crossing.sin_angle[0])) > PARALLEL_SIN:
            where = f"of group {group} at {describe_input(self.mechanism)}"
            lengths = [magnitude(complex(d if isinstance(d, complex) else d[0])) for d in (first[1], second[1])]
            if min(lengths) == 0.0:
                raise SingularityError(
                    f"singular position {where}: at joint {what} the {self.kind} construction fails because "
                    "a direction line has no direction; two joints of one link are at the same place")
            raise SingularityError(
                f"singular position {where}: at joint {what} the {self.kind} direction lines ({labels[0]}; "
                f"{labels[1]}) are parallel: the links that meet there are in line, or square to a slide (a "
                f"dead centre or change point), so the {self.kind} of {what} is not determined by the input")
        return crossing

    def step_line(self, line: Line, label: str) -> StepLine:
        """Row 0 of a direction line, for a step."""
        return StepLine(self.vec(line[0]), self.vec(line[1]), label)


@functools.lru_cache(maxsize=1024)
def _similar(wa: complex, wb: complex, at: complex, label: str, link: str) -> complex:
    """Where Mehmke's two lines cross for a polygon side of 1 from a to b: the image is a + (b - a) k.

    The line from a at the triangle's angle at A and the line from b at its angle at B are
    crossed for a = 0, b = 1; the image of a link is similar to it, so for any a and b they
    cross at a + (b - a) k. A flat triangle (lines at a sine below ``COLLINEAR_SIN``) takes k
    from proportional division instead: the foot's ratio along AB and the height over |AB|. It depends
    on the link's shape alone, so it is kept for the next polygon and the next sweep of that shape.
    """
    side = wb - wa
    if side == 0:
        raise SingularityError(f"image of {label}: two known points of link {link} coincide")
    ratio = (at - wa) / side
    ratio_b = (at - wb) / (wa - wb)
    turn_a, turn_b = cmath.exp(1j * phase(ratio)), cmath.exp(1j * phase(ratio_b))  # 1 at a corner
    crossing = cross_lines(np.zeros(1, np.complex128), np.array([turn_a]), 1.0 + 0j, np.array([-turn_b]))
    if not abs(float(crossing.sin_angle[0])) >= COLLINEAR_SIN:
        return ratio
    return complex(crossing.point[0])


def _key(wa: PointsLike, wb: PointsLike, at: PointsLike) -> Reals | float:
    """Which two known tips build an image: the pair with the largest |ab| + |ab x a->point|."""
    side = wb - wa
    return np.abs(side) + np.abs(cross(side, at - wa))
