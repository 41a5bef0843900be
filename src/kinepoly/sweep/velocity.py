"""The velocity polygon over rows: ``construct.velocity`` executed on arrays, dyad by dyad.

Per dyad the same two direction lines are drawn through the same known tips (perpendicular to
the link for a turning relative velocity, parallel to the slide for a sliding one) and crossed;
omega is read off the polygon as |v_B/A| / |AB| with the sense of v_B/A, exactly as the scalar
construction reads it (see ``read_rates``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import LinkInput, SliderInput, SliderSpec
from kinepoly.engine.plan import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.geom.arrays import Crossing, Points, Reals, turn
from kinepoly.sweep.polygon import ArrayPolygon, Line
from kinepoly.sweep.position import SweepPositions

__all__ = ["SweepVelocity", "link_length", "read_rates", "slide_direction", "sweep_velocity"]


@dataclass(frozen=True)
class SweepVelocity:
    """Tips, omegas and sliding velocities at every row, and the polygon (for tips asked later)."""

    polygon: ArrayPolygon
    sliding: dict[str, Points]
    line_sines: dict[str, Reals]

    @property
    def tips(self) -> dict[str, Points]:
        return self.polygon.tips

    @property
    def omega(self) -> dict[str, Reals]:
        return self.polygon.rate


def slide_direction(positions: SweepPositions, slider: SliderSpec) -> Points:
    return positions.poses[slider.guide].rotation * turn(slider.angle_rad)


def link_length(mechanism: Mechanism, link: str, a: str, b: str) -> float:
    """|ab| in ``link``'s own frame: the length of a direction k x ab drawn for that link."""
    (ax, ay), (bx, by) = mechanism.local(link, a), mechanism.local(link, b)
    return math.hypot(bx - ax, by - ay)


def read_rates(polygon: ArrayPolygon, crossing: Crossing, first: str | None, second: str | None) -> None:
    """Read omega (or alpha) off the polygon where a line perpendicular to a link was crossed.

    The line through the known tip a along k x AB meets the other line at a + t (k x AB), so the
    relative vector is t (k x AB): |v_B/A| / |AB| = |t|, counter-clockwise when t > 0. That t is
    the crossing's ``along_first`` (``along_second()`` for the second line).
    """
    if first is not None:
        polygon.set_rate(first, crossing.along_first)
    if second is not None:
        polygon.set_rate(second, crossing.along_second())


def _other(joint: Revolute | SliderSpec, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _drive(polygon: ArrayPolygon, sliding: dict[str, Points]) -> None:
    mech = polygon.mechanism
    inp = mech.scene.input
    if isinstance(inp, LinkInput):
        polygon.set_rate(inp.link, np.full(polygon.n, inp.omega))
    elif isinstance(inp, SliderInput):
        slider = mech.slider(inp.slider)
        rel = inp.s_dot * slide_direction(polygon.positions, slider)
        sliding[slider.name] = rel
        moving = slider.block if slider.guide == mech.ground else slider.guide
        polygon.add_tip(moving, slider.point, rel if moving == slider.block else -rel)


def _revolute_line(polygon: ArrayPolygon, known_link: str, known_point: str, point: str, link: str | None) -> Line:
    """Through the tip of known_point, perpendicular to known_point -> point (both points of ``link``,
    when given, so that the direction's length is that link's)."""
    start = polygon.tip(known_link, known_point)
    size = None if link is None else link_length(polygon.mechanism, link, known_point, point)
    return start, 1j * (polygon.world(point) - polygon.world(known_point)), size


def _slide_line(polygon: ArrayPolygon, slider: SliderSpec, other: str, point: str) -> Line:
    """Through the tip of point@other, parallel to the slide (a unit direction)."""
    return polygon.tip(other, point), slide_direction(polygon.positions, slider), 1.0


def _slide_rel(polygon: ArrayPolygon, slider: SliderSpec, link: str, point: str, sliding: dict[str, Points]) -> None:
    other = slider.guide if link == slider.block else slider.block
    on_link = polygon.tips[polygon.label(link, point)]
    on_other = polygon.tip(other, point)
    sliding[slider.name] = on_link - on_other if link == slider.block else on_other - on_link


def _dyad(polygon: ArrayPolygon, dyad: Dyad, sliding: dict[str, Points], sines: dict[str, Reals]) -> None:
    mech, i, j = polygon.mechanism, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        line1 = _revolute_line(polygon, _other(dyad.first_joint, i), p1, p2, i)
        if isinstance(dyad.second_joint, Revolute):
            line2 = _revolute_line(polygon, _other(dyad.second_joint, j), dyad.second_joint.point, p2, j)
        else:
            line2 = _slide_line(polygon, dyad.second_joint, _other(dyad.second_joint, j), p2)
        crossing = polygon.cross_lines(line1, line2, p2, dyad.name)
        polygon.add_tip(i, p2, crossing.point)
        read_rates(polygon, crossing, i, j if isinstance(dyad.second_joint, Revolute) else None)
        if isinstance(dyad.second_joint, SliderSpec):
            _slide_rel(polygon, dyad.second_joint, j, p2, sliding)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        line1 = _revolute_line(polygon, r.guide_known, r.guide_pin, r.block_pin, None)
        start2 = polygon.tip(r.block_known, r.block_pin)
        crossing = polygon.cross_lines(line1, (start2, slide_direction(polygon.positions, r.slider), 1.0),
                                       polygon.label(r.guide, r.block_pin), dyad.name)
        polygon.add_tip(r.guide, r.block_pin, crossing.point)
        read_rates(polygon, crossing, r.guide, None)
        sliding[r.slider.name] = start2 - crossing.point
    else:  # PRP and RPP: both links' omegas are known from their guides, two slide lines cross
        t = two_slide_roles(dyad, mech)
        if t.pin is not None and t.pin_known is not None:
            polygon.tip(t.pin_known, t.pin)
        line1 = _slide_line(polygon, t.first_slider, t.side1, t.point)
        line2 = _slide_line(polygon, t.second_slider, t.side2, t.point)
        crossing = polygon.cross_lines(line1, line2, t.point, dyad.name)
        polygon.add_tip(t.moving, t.point, crossing.point)
        _slide_rel(polygon, t.first_slider, t.first_relative, t.point, sliding)
        _slide_rel(polygon, t.second_slider, j, t.point, sliding)
    sines[dyad.name] = crossing.sin_angle


def sweep_velocity(mechanism: Mechanism, positions: SweepPositions, plan: PositionPlan,
                   wanted: tuple[tuple[str, str], ...] = ()) -> SweepVelocity:
    """The velocity polygon at every row for every group of ``plan``, then the tips of ``wanted``."""
    polygon = ArrayPolygon(mechanism, positions, "velocity")
    sliding: dict[str, Points] = {}
    sines: dict[str, Reals] = {}
    _drive(polygon, sliding)
    for group in plan.groups:
        if isinstance(group, Dyad):
            _dyad(polygon, group, sliding, sines)
        else:
            from kinepoly.sweep.newton import velocity_rows

            velocity_rows(polygon, group, sliding)
    for link, point in wanted:
        polygon.tip(link, point)
    return SweepVelocity(polygon, sliding, sines)
