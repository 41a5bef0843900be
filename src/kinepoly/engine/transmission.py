"""The transmission angle of each dyad: the angle at which its two velocity direction lines cross.

For a four-bar's output dyad the lines are perpendicular to the coupler and to the rocker, so
the angle is the textbook one between coupler and rocker; for a slider-crank, between the rod
and the normal to the slide; for a slotted lever, between the slot's normal and the lever; for
two slides, between their lines. It is reported acute, from 0 to 90 degrees: 90 transmits best,
0 is a dead point, where the velocity lines are parallel and the construction fails (the force
that drives the output link is then all spent pressing on its bearing). A group solved by
Newton's method has no two lines and no transmission angle.

Over rows: a sweep reads every row, a solve row 0 (``Transmission.angle_deg``).
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct

from kinepoly.engine.groups import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.engine.position import Positions
from kinepoly.engine.velocity import slide_direction
from kinepoly.geom.arrays import Points, Reals, length
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import SliderSpec

__all__ = ["Transmission", "TransmissionPair", "Way", "transmission_angles", "transmission_pairs"]


class Transmission(Struct, frozen=True):
    """The transmission angle of one dyad at every row, and what it is between.

    ``point`` is the point whose velocity the dyad's two lines find (it names the sweep's column);
    ``joint`` the joint the angle is at, as warnings name it (the same point but in an RPP dyad,
    where it is the inner slide's point).
    """

    group: str
    point: str
    joint: str
    between: str
    at_zero: str
    """What a zero transmission angle means here, in words (a dead centre of this dyad)."""
    angle: Reals
    """In radians, folded into [0, pi/2]."""

    @property
    def angle_deg(self) -> float:
        """Row 0's angle in degrees (a solve's)."""
        return math.degrees(float(self.angle[0]))


_CLEAR = 1e-150
"""Where the cross or the dot product of the two directions is at least this (and finite) at every row, both
directions have a length there, and the product of the lengths does not round to zero (it is at least half
this): the angle needs no row's directions measured."""

Way = tuple[str, str] | SliderSpec
"""How a direction line of a dyad runs: square to the chord from one point to another of a link (``Positions.chord``,
the direction its velocity construction drew), or along a slide (``slide_direction``)."""


class TransmissionPair(Struct, frozen=True):
    """What one dyad's transmission angle is between, found once for a plan: its two direction lines (``Way``), the
    point and joint it names, and the words of the angle (``Transmission``)."""

    group: str
    point: str
    joint: str
    between: str
    at_zero: str
    first: Way
    second: Way

    def angle(self, positions: Positions) -> Transmission:
        """The angle at every row of ``positions``, with what it is between."""
        return Transmission(self.group, self.point, self.joint, self.between, self.at_zero, self.radians(positions))

    def radians(self, positions: Positions) -> Reals:
        """The angle at every row of ``positions``, in radians, folded into [0, pi/2].

        It is the angle whose tangent is |cross| / |dot| of the two directions: well conditioned everywhere. (The
        arcsine of the crossing's sine, which the construction has already, loses half the digits near 90 degrees,
        where its slope grows without limit: up to 2e-6 degrees there.) A direction of no length (two points of a
        link in one place) is taken as 90 degrees.
        """
        first, second = _direction(positions, self.first), _direction(positions, self.second)
        product = positions.chord_product(first, second)  # made for the polygons' crossing of these lines
        if product is None:
            product = np.conjugate(first) * second  # its imaginary part the cross product, its real part the dot
        across, along = np.abs(product.imag), np.abs(product.real)
        turn = np.arctan2(across, along)
        if (np.minimum.reduce(across) >= _CLEAR or np.minimum.reduce(along) >= _CLEAR) \
                and math.isfinite(np.add.reduce(across) + np.add.reduce(along)):
            return turn  # every direction has a length: no row is taken as 90 degrees
        return np.where(length(first) * length(second) > 0.0, turn, np.pi / 2)


def _direction(positions: Positions, way: Way) -> Points:
    if isinstance(way, SliderSpec):
        return slide_direction(positions, way)
    return positions.chord(way[0], way[1])[1]


def _pair(mechanism: Mechanism, dyad: Dyad) -> TransmissionPair:
    """The dyad's two velocity directions, its point and joint, and the words of the angle."""
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        second = dyad.second_joint
        if isinstance(second, Revolute):
            p3 = second.point
            return TransmissionPair(dyad.name, p2, p2, f"{p1}{p2} and {p3}{p2}",
                                    f"the links {p1}{p2} and {p3}{p2} are in line", (p1, p2), (p3, p2))
        assert isinstance(second, SliderSpec)
        return TransmissionPair(dyad.name, p2, p2, f"{p1}{p2} and the normal to slider {second.name}",
                                f"the link {p1}{p2} is square to slider {second.name}'s line", (p1, p2), second)
    if dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p, name = r.guide_pin, r.block_pin, r.slider.name
        return TransmissionPair(dyad.name, p, p, f"the normal to slider {name} and the path of {p} about {q}",
                                f"slider {name}'s line is square to {q}{p}", (q, p), r.slider)
    t = two_slide_roles(dyad, mechanism)
    a, b = t.first_slider, t.second_slider
    assert isinstance(a, SliderSpec) and isinstance(b, SliderSpec)
    return TransmissionPair(dyad.name, t.point, a.point, f"sliders {a.name} and {b.name}",
                            f"the lines of sliders {a.name} and {b.name} are parallel", a, b)


def transmission_pairs(mechanism: Mechanism, plan: PositionPlan) -> tuple[TransmissionPair, ...]:
    """What the transmission angle of every dyad of the plan is between, in the plan's order: the same for every
    row and every call (a prepared sweep finds them once); ``mechanism``: the plan's (or one of other dimensions,
    the same names)."""
    return tuple(_pair(mechanism, group) for group in plan.groups if isinstance(group, Dyad))


def transmission_angles(positions: Positions, plan: PositionPlan) -> list[Transmission]:
    """The transmission angle of every dyad of the plan, in the plan's order, a solve's and a sweep's alike
    (``TransmissionPair.angle``)."""
    return [pair.angle(positions) for pair in transmission_pairs(positions.mechanism, plan)]
