"""A triad's leg made of two links held together by a driven joint (a cylinder's barrel and rod).

Once the input is given, a cylinder from a known link at K to the ternary at Q (the barrel ``carrier``
pinned at K, the rod ``link`` pinned at Q, or the other way round) holds Q at a known distance from K:
the two links are one binary leg K Q whose length changes at a known rate. Its direction in the polygons
is that of a pin leg, square to K Q, after the drive's relative term (``engine.carry``):

    v_Q = v_K + v_Q/Q@c + v_Q@c/K,             v_Q@c/K square to K Q (omega of the carrier), and
    a_Q = a_K + a^n_Q@c/K + a_Q/Q@c + a^t_Q@c/K, a_Q/Q@c = s_ddot e + 2 omega x s_dot e for a cylinder

(a motor between the two links gives its own relative terms). The leg's line on the mechanism, through
which the Assur point is found, is K Q itself. ``engine.triad`` builds the group; this module gives the
leg's known terms, and reads the carrier's rate, its point under Q and the slider's values after.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from msgspec import Struct

from kinepoly.engine.carry import relative_acceleration, relative_velocity
from kinepoly.engine.lines import add_motor_rate, read_rate, record_drive_term, slide_direction
from kinepoly.engine.polygon import Polygon
from kinepoly.engine.results import AccelerationContext
from kinepoly.engine.steps import DrawnVector
from kinepoly.geom.arrays import Points, Reals
from kinepoly.model.mechanism import Drive, Revolute
from kinepoly.scene.spec import SliderSpec

__all__ = ["Leg", "acceleration_terms", "finish_acceleration", "finish_velocity", "velocity_terms"]


class Leg(Struct, frozen=True):
    """One leg of a triad (see ``engine.triad``): its kind, its own link, the point Q, the known link it joins,
    the outer pin K (a pin or slot leg) and the slider (a slide or slot leg)."""

    kind: Literal["pin", "slide", "slot", "face"]
    link: str
    point: str
    known: str
    pin: str | None
    slider: SliderSpec | None
    equivalent: str = ""
    """A spline cam pair's name where the leg is its equivalent link K W (``link`` names it, K on the cam is
    ``pin``, W on the ternary ``point``): a link at this instant only, whose omega is kept with the pair; or,
    for a flat face (kind ``face``), the block pinned to the cam at K (``point``) sliding along the ternary's
    face, whose velocity over the face is kept with the pair."""
    carrier: str = ""
    """A driven leg's other link, pinned to the known link at ``pin`` (``link`` is pinned to the ternary)."""
    drive: Drive | None = None
    """A driven leg's input, the joint between ``carrier`` and ``link``."""

    @property
    def name(self) -> str:
        """The leg as the steps name it: its link, or both links of a driven leg (``5+6``)."""
        return f"{self.carrier}+{self.link}" if self.carrier else self.link


def _drive(leg: Leg) -> Drive:
    assert leg.drive is not None and leg.pin is not None
    return leg.drive


def _geometry(polygon: Polygon, leg: Leg) -> tuple[Points, Points | None, Points | None]:
    """Where Q is, the motor's pin (or None), the slide's unit direction (or None)."""
    joint = _drive(leg).joint
    at = polygon.world(leg.point)
    if isinstance(joint, Revolute):
        return at, polygon.world(joint.point), None
    return at, None, slide_direction(polygon.positions, joint)


def _relative_velocity(polygon: Polygon, leg: Leg) -> Points:
    at, pin, slide = _geometry(polygon, leg)
    return relative_velocity(_drive(leg), leg.link, at, pin, slide)


def _relative_acceleration(ctx: AccelerationContext, leg: Leg) -> Points:
    b = ctx.b
    at, pin, slide = _geometry(b, leg)
    joint = _drive(leg).joint
    guide = joint.guide if isinstance(joint, SliderSpec) else leg.carrier
    return relative_acceleration(_drive(leg), leg.link, at, pin, slide, b.omega_of(leg.link), b.omega_of(leg.carrier),
                                 b.omega_of(guide))


def _term(polygon: Polygon, leg: Leg) -> str:
    return f"{polygon.symbol}_{leg.point}/{polygon.label(leg.carrier, leg.point)}"


def velocity_terms(polygon: Polygon, leg: Leg) -> tuple[Points, Points, tuple[DrawnVector, ...]]:
    """The leg's line in the velocity polygon: through the tip of K plus the drive's term, square to K Q;
    with the term laid (its step recorded)."""
    assert leg.pin is not None
    start = polygon.tip(leg.known, leg.pin)
    end = np.asarray(start + _relative_velocity(polygon, leg))
    direction = np.asarray(1j * (polygon.world(leg.point) - polygon.world(leg.pin)))
    if not polygon.record:
        return end, direction, ()
    term = _term(polygon, leg)
    record_drive_term(polygon, _drive(leg), term, start, end, leg.point, leg.carrier,
                      polygon.label(leg.known, leg.pin).lower())
    return end, direction, (DrawnVector(term, polygon.vec(start), polygon.vec(end), "relative"),)


def acceleration_terms(ctx: AccelerationContext, leg: Leg) -> tuple[Points, Points, tuple[DrawnVector, ...]]:
    """The leg's line in the acceleration polygon: after the carrier's normal term toward K and the drive's
    relative term (its step recorded), square to K Q."""
    b = ctx.b
    assert leg.pin is not None
    (start, direction, _), normal, _ = ctx.normal_line(leg.known, leg.pin, leg.point, leg.carrier, rigid=False)
    end = np.asarray(start + _relative_acceleration(ctx, leg))
    if not b.record:
        return end, np.asarray(direction), ()
    term = _term(b, leg)
    on_carrier = b.label(leg.carrier, leg.point)
    vectors = [] if normal is None else [DrawnVector(f"a^n_{on_carrier}/{leg.pin}", normal.start, normal.end, "normal")]
    record_drive_term(b, _drive(leg), term, start, end, leg.point, leg.carrier,
                      vectors[0].label if vectors else b.label(leg.known, leg.pin).lower())
    return end, np.asarray(direction), (*vectors, DrawnVector(term, b.vec(start), b.vec(end), "relative"))


def _finish(polygon: Polygon, leg: Leg, tip: Points, along: Reals, relative: Points) -> None:
    """The carrier's rate read off the leg's line, its point under Q (the tip less the drive's term, found
    with Q's tip, as in a carried dyad), and a motor's rate."""
    assert leg.pin is not None
    polygon.add_tip(leg.carrier, leg.point, np.asarray(tip - relative))
    read_rate(polygon, leg.carrier, leg.pin, polygon.label(leg.carrier, leg.point), along)
    drive = _drive(leg)
    if isinstance(drive.joint, Revolute):
        add_motor_rate(polygon, drive, leg.link, leg.carrier, along)


def finish_velocity(polygon: Polygon, leg: Leg, tip: Points, along: Reals, sliding: dict[str, Points]) -> None:
    """After the construction: the carrier's omega and point under Q; a cylinder's sliding velocity."""
    relative = _relative_velocity(polygon, leg)
    _finish(polygon, leg, tip, along, relative)
    joint = _drive(leg).joint
    if isinstance(joint, SliderSpec):
        sign = 1.0 if leg.link == joint.block else -1.0
        sliding[joint.name] = np.asarray(sign * relative)


def finish_acceleration(ctx: AccelerationContext, leg: Leg, tip: Points, along: Reals) -> None:
    """After the construction: the carrier's alpha and point under Q; a cylinder's sliding and Coriolis terms."""
    _finish(ctx.b, leg, tip, along, _relative_acceleration(ctx, leg))
    joint = _drive(leg).joint
    if isinstance(joint, SliderSpec):
        ctx.slide_values(joint, joint.block, joint.point)
