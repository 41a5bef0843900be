"""The acceleration polygon over rows: ``construct.acceleration`` executed on arrays, dyad by dyad.

The known terms are laid end to end as the scalar construction lays them (normal terms
-omega^2 r toward the centre; Coriolis terms 2 omega x v_rel where a block slides on a guide
that can turn), then the same two direction lines (tangential: perpendicular to the link;
sliding: along the slide) are crossed. Alpha is read off the tangential term.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import LinkInput, SliderInput, SliderSpec
from kinepoly.engine.plan import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.geom.arrays import Points, Reals
from kinepoly.sweep.polygon import ArrayPolygon, Line
from kinepoly.sweep.position import SweepPositions
from kinepoly.sweep.velocity import SweepVelocity, link_length, read_rates, slide_direction

__all__ = ["AccelerationContext", "SweepAcceleration", "sweep_acceleration"]


@dataclass(frozen=True)
class SweepAcceleration:
    """Tips, alphas, sliding accelerations and Coriolis terms at every row."""

    polygon: ArrayPolygon
    sliding: dict[str, Points]
    coriolis: dict[str, Points]

    @property
    def tips(self) -> dict[str, Points]:
        return self.polygon.tips

    @property
    def alpha(self) -> dict[str, Reals]:
        return self.polygon.rate


class AccelerationContext:
    """The polygon being built, the velocity polygon it stands on, and the slider terms found."""

    def __init__(self, polygon: ArrayPolygon, velocity: SweepVelocity) -> None:
        self.b = polygon
        self.v = velocity
        self.sliding: dict[str, Points] = {}
        self.coriolis: dict[str, Points] = {}

    def v_tip(self, link: str, point: str) -> Points:
        if link == self.b.mechanism.ground:
            return self.b.zero
        return self.v.tips[self.b.label(link, point)]

    def normal_line(self, known_link: str, known_point: str, point: str, moving: str, rigid: bool = True) -> Line:
        """a_known + a^n (toward known_point), then the line perpendicular to known_point -> point
        (``rigid``: both are points of ``moving``, so the direction's length is a link length)."""
        b = self.b
        start = b.tip(known_link, known_point)
        r = b.world(point) - b.world(known_point)
        w = b.omega_of(moving)
        size = link_length(b.mechanism, moving, known_point, point) if rigid else None
        return np.asarray(start - (w * w) * r), 1j * r, size

    def slide_line(self, slider: SliderSpec, other: str, moving: str, point: str) -> Line:
        """a_point@other (+ the Coriolis term where the guide turns), then the line along the slide."""
        b = self.b
        start = b.tip(other, point)
        if b.mechanism.has_turning_guide(slider):
            w = b.omega_of(other)
            v_rel = self.v_tip(moving, point) - self.v_tip(other, point)
            start = np.asarray(start + (2.0 * w) * (1j * v_rel))
        return start, slide_direction(b.positions, slider), 1.0

    def slide_values(self, slider: SliderSpec, link: str, point: str) -> None:
        """Sliding acceleration and Coriolis term of the block relative to the guide."""
        b = self.b
        other = slider.guide if link == slider.block else slider.block
        block_side, guide_side = (link, other) if link == slider.block else (other, link)
        a_block, a_guide = b.tip(block_side, point), b.tip(guide_side, point)
        v_rel = self.v_tip(block_side, point) - self.v_tip(guide_side, point)
        cor = (2.0 * b.omega_of(slider.guide)) * (1j * v_rel)
        self.coriolis[slider.name] = cor
        self.sliding[slider.name] = a_block - a_guide - cor


def _other(joint: Revolute | SliderSpec, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _dyad(ctx: AccelerationContext, dyad: Dyad) -> None:
    b, i, j = ctx.b, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        line1 = ctx.normal_line(_other(dyad.first_joint, i), p1, p2, i)
        if isinstance(dyad.second_joint, Revolute):
            line2 = ctx.normal_line(_other(dyad.second_joint, j), dyad.second_joint.point, p2, j)
        else:
            line2 = ctx.slide_line(dyad.second_joint, _other(dyad.second_joint, j), j, p2)
        crossing = b.cross_lines(line1, line2, p2, dyad.name)
        b.add_tip(i, p2, crossing.point)
        read_rates(b, crossing, i, j if isinstance(dyad.second_joint, Revolute) else None)
        if isinstance(dyad.second_joint, SliderSpec):
            ctx.slide_values(dyad.second_joint, j, p2)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        line1 = ctx.normal_line(r.guide_known, r.guide_pin, r.block_pin, r.guide, rigid=False)
        end = b.tip(r.block_known, r.block_pin)
        if b.mechanism.has_turning_guide(r.slider):
            w = b.omega_of(r.guide)
            v_rel = ctx.v_tip(r.guide, r.block_pin) - ctx.v_tip(r.block, r.block_pin)
            end = np.asarray(end + (2.0 * w) * (1j * v_rel))
        crossing = b.cross_lines(line1, (end, slide_direction(b.positions, r.slider), 1.0),
                                 b.label(r.guide, r.block_pin), dyad.name)
        b.add_tip(r.guide, r.block_pin, crossing.point)
        read_rates(b, crossing, r.guide, None)
        ctx.slide_values(r.slider, r.block, r.block_pin)
    else:
        t = two_slide_roles(dyad, b.mechanism)
        if t.pin is not None and t.pin_known is not None:
            b.tip(t.pin_known, t.pin)
        line1 = ctx.slide_line(t.first_slider, t.side1, t.moving, t.point)
        line2 = ctx.slide_line(t.second_slider, t.side2, j, t.point)
        crossing = b.cross_lines(line1, line2, t.point, dyad.name)
        b.add_tip(t.moving, t.point, crossing.point)
        ctx.slide_values(t.first_slider, t.first_relative, t.point)
        ctx.slide_values(t.second_slider, j, t.point)


def _drive(ctx: AccelerationContext) -> None:
    b = ctx.b
    mech = b.mechanism
    inp = mech.scene.input
    if isinstance(inp, LinkInput):
        b.set_rate(inp.link, np.full(b.n, inp.alpha))
    elif isinstance(inp, SliderInput):
        slider = mech.slider(inp.slider)
        rel = inp.s_ddot * slide_direction(b.positions, slider)
        moving = slider.block if slider.guide == mech.ground else slider.guide
        b.add_tip(moving, slider.point, rel if moving == slider.block else -rel)
        ctx.sliding[slider.name] = rel
        ctx.coriolis[slider.name] = b.zero


def sweep_acceleration(mechanism: Mechanism, positions: SweepPositions, plan: PositionPlan, velocity: SweepVelocity,
                       wanted: tuple[tuple[str, str], ...] = ()) -> SweepAcceleration:
    """The acceleration polygon at every row, on top of the velocity polygon."""
    polygon = ArrayPolygon(mechanism, positions, "acceleration", omega=velocity.omega)
    ctx = AccelerationContext(polygon, velocity)
    _drive(ctx)
    for group in plan.groups:
        if isinstance(group, Dyad):
            _dyad(ctx, group)
        else:
            from kinepoly.sweep.newton import acceleration_rows

            acceleration_rows(ctx, group)
    for link, point in wanted:
        polygon.tip(link, point)
    return SweepAcceleration(polygon, ctx.sliding, ctx.coriolis)
