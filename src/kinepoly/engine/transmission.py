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
from dataclasses import dataclass

import numpy as np

from kinepoly.engine.groups import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.engine.position import Positions
from kinepoly.engine.velocity import slide_direction
from kinepoly.geom.arrays import Points, Reals, length
from kinepoly.model.mechanism import Revolute
from kinepoly.scene.spec import SliderSpec

__all__ = ["Transmission", "transmission_angles"]


@dataclass(frozen=True, repr=False)
class Transmission:
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


def _describe(positions: Positions, dyad: Dyad) -> tuple[tuple[Points, Points], str, str, str, str]:
    """The dyad's two velocity directions, its point and joint, and the words of the angle. A direction square to a
    link is the one its velocity construction drew (``Positions.chord``, made once)."""
    def square(start: str, end: str) -> Points:
        return positions.chord(start, end)[1]

    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        second = dyad.second_joint
        if isinstance(second, Revolute):
            p3 = second.point
            return ((square(p1, p2), square(p3, p2)), p2, p2,
                    f"{p1}{p2} and {p3}{p2}", f"the links {p1}{p2} and {p3}{p2} are in line")
        return ((square(p1, p2), slide_direction(positions, second)), p2, p2,
                f"{p1}{p2} and the normal to slider {second.name}",
                f"the link {p1}{p2} is square to slider {second.name}'s line")
    if dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p, name = r.guide_pin, r.block_pin, r.slider.name
        return ((square(q, p), slide_direction(positions, r.slider)), p, p,
                f"the normal to slider {name} and the path of {p} about {q}",
                f"slider {name}'s line is square to {q}{p}")
    t = two_slide_roles(dyad, positions.mechanism)
    a, b = t.first_slider, t.second_slider
    assert isinstance(a, SliderSpec)
    return ((slide_direction(positions, a), slide_direction(positions, b)), t.point, a.point,
            f"sliders {a.name} and {b.name}", f"the lines of sliders {a.name} and {b.name} are parallel")


def transmission_angles(positions: Positions, plan: PositionPlan) -> list[Transmission]:
    """The transmission angle of every dyad of the plan, in the plan's order, a solve's and a sweep's alike.

    It is the angle whose tangent is |cross| / |dot| of the two directions: well conditioned everywhere. (The
    arcsine of the crossing's sine, which the construction has already, loses half the digits near 90 degrees,
    where its slope grows without limit: up to 2e-6 degrees there.) A direction of no length (two points of a
    link in one place) is taken as 90 degrees.
    """
    out = []
    for group in plan.groups:
        if isinstance(group, Dyad):
            (first, second), point, joint, between, at_zero = _describe(positions, group)
            product = np.conjugate(first) * second  # its imaginary part the cross product, its real part the dot
            turn = np.arctan2(np.abs(product.imag), np.abs(product.real))
            angle = np.where(length(first) * length(second) > 0.0, turn, np.pi / 2)
            out.append(Transmission(group.name, point, joint, between, at_zero, angle))
    return out
