"""The velocity polygon, constructed dyad by dyad by crossing two direction lines, over rows.

For each dyad the unknown tip is where two lines through known tips cross: perpendicular to
the link for a turning relative velocity (v_B/A is perpendicular to AB), parallel to the slide
for a sliding one. Omega of a link is then read off the polygon, |v_B/A| / |AB| with the sense
of v_B/A: the line through a along k x AB meets the other at a + t (k x AB), so omega = t, the
crossing's ``along`` (``read_rate``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinepoly.engine.closures import other_side
from kinepoly.engine.plan import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.engine.polygon import CrossLines, Line, Polygon, sense
from kinepoly.engine.position import Positions
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import Crossing, Points, Reals, cross_lines, turn
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput, SliderSpec

__all__ = ["VelocityResult", "construct_velocity", "link_length", "read_rate", "slide_direction"]


@dataclass(frozen=True)
class VelocityResult:
    """The velocity polygon at every row: tips, omegas, sliding velocities, crossings and steps."""

    polygon: Polygon
    sliding: dict[str, Points]
    line_sines: dict[str, Reals]

    @property
    def tips(self) -> dict[str, Points]:
        return self.polygon.tips

    @property
    def omega(self) -> dict[str, Reals]:
        return self.polygon.rate


def slide_direction(positions: Positions, slider: SliderSpec) -> Points:
    """The unit direction of a slide at every row (it turns with the guide)."""
    return np.asarray(positions.poses[slider.guide].rotation * turn(slider.angle_rad))


def link_length(mechanism: Mechanism, link: str, a: str, b: str) -> float:
    """|ab| in ``link``'s own frame: the length of a direction k x ab drawn for that link."""
    (ax, ay), (bx, by) = mechanism.local(link, a), mechanism.local(link, b)
    return math.hypot(bx - ax, by - ay)


def read_rate(polygon: Polygon, link: str, first: str, second: str, along: Reals) -> None:
    """Read omega (or alpha, from a tangential term) of ``link`` off the polygon, with its step.

    The crossing lies ``along`` direction vectors k x (first -> second) from the known tip, so the
    relative vector is along * (k x r): |term| / |r| = |along|, counter-clockwise when positive.
    """
    polygon.set_rate(link, along)
    if not polygon.record:
        return
    value = polygon.num(along)
    length = abs(complex(polygon.world(second.partition("@")[0])[0] - polygon.world(first)[0]))
    symbol = "omega" if polygon.kind == "velocity" else "alpha"
    term = f"v_{second}/{first}" if polygon.kind == "velocity" else f"a^t_{second}/{first}"
    ground = polygon.ground_name()
    polygon.step(Step(polygon=polygon.kind, kind="read", equation=f"{symbol}{ground}{link} = |{term}| / |{first}{second}|",
                      result=f"{symbol}{ground}{link}", value=(value,), topic="read",
                      params=(("link", link), ("ground", ground), ("term", term), ("first", first),
                              ("second", second), ("magnitude", abs(value) * length), ("length", length),
                              ("rate", abs(value)), ("sense", sense(value)))))


def _drive(polygon: Polygon, sliding: dict[str, Points]) -> None:
    mech = polygon.mechanism
    inp = mech.scene.input
    if isinstance(inp, LinkInput):
        polygon.set_rate(inp.link, np.full(polygon.n, inp.omega))
        if polygon.record:
            polygon.step(Step(polygon="velocity", kind="known", equation=f"omega{mech.ground}{inp.link} given",
                              result=f"omega{mech.ground}{inp.link}", value=(inp.omega,), topic="input-rate",
                              params=(("link", inp.link), ("ground", mech.ground or ""), ("rate", abs(inp.omega)),
                                      ("sense", sense(inp.omega)))))
    elif isinstance(inp, SliderInput):
        slider = mech.slider(inp.slider)
        sliding[slider.name] = lay_driven_slider(polygon, slider, inp.s_dot)
    elif isinstance(inp, GivenInput):
        _given(polygon, inp)


def lay_driven_slider(polygon: Polygon, slider: SliderSpec, amount: float) -> Points:
    """The tip of a driven slider's point: ``amount`` (s_dot or s_ddot) along the slide, from o.

    Returns the block's motion relative to the guide (the guide or the block is the frame).
    """
    rel = np.asarray(amount * slide_direction(polygon.positions, slider))
    moving = slider.block if slider.guide == polygon.mechanism.ground else slider.guide
    value = rel if moving == slider.block else -rel
    label = polygon.add_tip(moving, slider.point, value)
    if polygon.record:
        name = "s_dot" if polygon.kind == "velocity" else "s_ddot"
        symbol = polygon.symbol
        polygon.step(Step(polygon=polygon.kind, kind="known",
                          equation=f"{symbol}_{label} = {name}{slider.name} along the slide", result=label.lower(),
                          known=((f"{symbol}_{label}", "magnitude and direction"),),
                          vectors=(DrawnVector(f"{symbol}_{label}", (0.0, 0.0), polygon.vec(value), "absolute"),),
                          value=polygon.vec(value), topic="driven-slider",
                          params=(("slider", slider.name), ("point", label), ("amount", amount))))
    return rel


def _given(polygon: Polygon, given: GivenInput) -> None:
    link = polygon.mechanism.link_names[0]
    for g in given.points:
        value = np.full(polygon.n, complex(*g.velocity))
        polygon.add_tip(link, g.name, value)
        if polygon.record:
            polygon.step(Step(polygon="velocity", kind="known", equation=f"v_{g.name} given", result=g.name.lower(),
                              known=((f"v_{g.name}", "magnitude and direction"),),
                              vectors=(DrawnVector(f"v_{g.name}", (0.0, 0.0), g.velocity, "absolute"),),
                              value=g.velocity, topic="given-point",
                              params=(("point", g.name), ("magnitude", math.hypot(*g.velocity)))))
    first, second = given.points[0], given.points[1]
    at = polygon.world(second.name) - polygon.world(first.name)
    rel = complex(*second.velocity) - complex(*first.velocity)
    along = float(np.real(np.conj(at[0] / abs(at[0])) * rel))
    if abs(along) > 1e-9 * max(math.hypot(*first.velocity), math.hypot(*second.velocity), 1e-300):
        raise SceneError(f"{polygon.mechanism.scene.source}: given.{second.name}.velocity: the given velocities of "
                         f"{first.name} and {second.name} differ by {along:.6g} {polygon.unit} along "
                         f"{first.name}{second.name}; a rigid body allows none (make v_{second.name}/{first.name} "
                         f"perpendicular to {first.name}{second.name})")
    read_rate(polygon, link, first.name, second.name, np.asarray((rel / (1j * at)).real))


def _revolute_line(polygon: Polygon, known_link: str, known_point: str, point: str, link: str | None) -> Line:
    """Through the tip of known_point, perpendicular to known_point -> point (both points of ``link``,
    when given, so that the direction's length is that link's)."""
    start = polygon.tip(known_link, known_point)
    size = None if link is None else link_length(polygon.mechanism, link, known_point, point)
    return start, np.asarray(1j * (polygon.world(point) - polygon.world(known_point))), size


def _perpendicular(polygon: Polygon, term: str, known_link: str, known_point: str, point: str) -> Direction:
    """What ``_revolute_line`` draws, as data."""
    return Direction(term, "perpendicular", f"{known_point}{point}", polygon.label(known_link, known_point).lower())


def _parallel(polygon: Polygon, term: str, slider: SliderSpec, other: str, point: str) -> Direction:
    """What ``_slide_line`` draws, as data."""
    return Direction(term, "parallel", slider.name, polygon.label(other, point).lower())


def _slide_line(polygon: Polygon, slider: SliderSpec, other: str, point: str) -> Line:
    """Through the tip of point@other, parallel to the slide (a unit direction)."""
    return polygon.tip(other, point), slide_direction(polygon.positions, slider), 1.0


def _perpendicular_label(polygon: Polygon, known_link: str, known_point: str, point: str) -> str:
    return f"perpendicular to {known_point}{point} through {polygon.label(known_link, known_point).lower()}"


def _parallel_label(slider: SliderSpec, through: str) -> str:
    return f"parallel to slider {slider.name} through {through.lower()}"


def _record_intersection(polygon: Polygon, label: str, equation: str, first: Line, second: Line,
                         line_labels: tuple[str, str], crossing: Crossing, known: tuple[tuple[str, str], ...],
                         directions: tuple[Direction, Direction]) -> None:
    polygon.step(Step(polygon="velocity", kind="intersection", equation=equation, result=label.lower(), known=known,
                      lines=(polygon.step_line(first, line_labels[0]), polygon.step_line(second, line_labels[1])),
                      value=polygon.vec(crossing.point), topic="intersection", params=(("point", label),),
                      directions=directions))


def _slide_rel(polygon: Polygon, slider: SliderSpec, link: str, point: str, sliding: dict[str, Points]) -> None:
    """Velocity of the block relative to the guide, from the tips of ``point`` on both sides."""
    other = slider.guide if link == slider.block else slider.block
    on_link = polygon.tips[polygon.label(link, point)]
    on_other = polygon.tip(other, point)
    sliding[slider.name] = np.asarray(on_link - on_other if link == slider.block else on_other - on_link)


def _known_pairs(*terms: tuple[str, str]) -> tuple[tuple[str, str], ...]:
    """(term, what is known of it) for the four terms of a dyad's equation: known, direction, known, direction."""
    return tuple((term, "magnitude and direction" if k % 2 == 0 else "direction") for k, term in
                 enumerate(t for pair in terms for t in pair))


def _dyad(polygon: Polygon, dyad: Dyad, sliding: dict[str, Points], sines: dict[str, Reals]) -> None:
    mech, i, j = polygon.mechanism, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        k1 = other_side(dyad.first_joint, i)
        line1 = _revolute_line(polygon, k1, p1, p2, i)
        label1 = _perpendicular_label(polygon, k1, p1, p2)
        if isinstance(dyad.second_joint, Revolute):
            p3 = dyad.second_joint.point
            k2 = other_side(dyad.second_joint, j)
            line2 = _revolute_line(polygon, k2, p3, p2, j)
            label2 = _perpendicular_label(polygon, k2, p3, p2)
        else:
            k2 = other_side(dyad.second_joint, j)
            line2 = _slide_line(polygon, dyad.second_joint, k2, p2)
            label2 = _parallel_label(dyad.second_joint, polygon.label(k2, p2))
        crossing = polygon.cross_lines(line1, line2, p2, dyad.name, (label1, label2))
        polygon.add_tip(i, p2, crossing.point)
        if polygon.record:
            direction1 = _perpendicular(polygon, f"v_{p2}/{p1}", k1, p1, p2)
            if isinstance(dyad.second_joint, Revolute):
                p3 = dyad.second_joint.point
                direction2 = _perpendicular(polygon, f"v_{p2}/{p3}", k2, p3, p2)
                equation = f"v_{p2} = v_{p1} + v_{p2}/{p1} = v_{p3} + v_{p2}/{p3}"
                known = _known_pairs((f"v_{p1}", f"v_{p2}/{p1}"), (f"v_{p3}", f"v_{p2}/{p3}"))
            else:
                at2 = polygon.label(k2, p2)
                direction2 = _parallel(polygon, f"v_{p2}/{at2}", dyad.second_joint, k2, p2)
                equation = f"v_{p2} = v_{p1} + v_{p2}/{p1} = v_{at2} + v_{p2}/{at2}"
                known = _known_pairs((f"v_{p1}", f"v_{p2}/{p1}"), (f"v_{at2}", f"v_{p2}/{at2}"))
            _record_intersection(polygon, p2, equation, line1, line2, (label1, label2), crossing, known,
                                 (direction1, direction2))
        read_rate(polygon, i, p1, p2, crossing.along_first)
        if isinstance(dyad.second_joint, Revolute):
            read_rate(polygon, j, dyad.second_joint.point, p2, crossing.along_second())
        else:
            _slide_rel(polygon, dyad.second_joint, j, p2, sliding)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p = r.guide_pin, r.block_pin
        line1 = _revolute_line(polygon, r.guide_known, q, p, None)
        start = polygon.tip(r.block_known, p)
        line2 = (start, slide_direction(polygon.positions, r.slider), 1.0)
        at = polygon.label(r.guide, p)
        labels = (_perpendicular_label(polygon, r.guide_known, q, p), _parallel_label(r.slider, p))
        crossing = polygon.cross_lines(line1, line2, at, dyad.name, labels)
        polygon.add_tip(r.guide, p, crossing.point)
        if polygon.record:
            _record_intersection(polygon, at, f"v_{at} = v_{q} + v_{at}/{q} = v_{p} + v_{at}/{p}", line1, line2,
                                 labels, crossing, _known_pairs((f"v_{q}", f"v_{at}/{q}"), (f"v_{p}", f"v_{at}/{p}")),
                                 (_perpendicular(polygon, f"v_{at}/{q}", r.guide_known, q, p),
                                  _parallel(polygon, f"v_{at}/{p}", r.slider, r.block_known, p)))
        read_rate(polygon, r.guide, q, at, crossing.along_first)
        sliding[r.slider.name] = np.asarray(start - crossing.point)
    else:  # PRP and RPP: both links' omegas are known from their guides, two slide lines cross
        t = two_slide_roles(dyad, mech)
        if t.pin is not None and t.pin_known is not None:
            polygon.tip(t.pin_known, t.pin)
        point = t.point
        line1 = _slide_line(polygon, t.first_slider, t.side1, point)
        line2 = _slide_line(polygon, t.second_slider, t.side2, point)
        a1, a2 = polygon.label(t.side1, point), polygon.label(t.side2, point)
        labels = (_parallel_label(t.first_slider, a1), _parallel_label(t.second_slider, a2))
        crossing = polygon.cross_lines(line1, line2, point, dyad.name, labels)
        polygon.add_tip(t.moving, point, crossing.point)
        if polygon.record:
            _record_intersection(polygon, point, f"v_{point} = v_{a1} + v_{point}/{a1} = v_{a2} + v_{point}/{a2}",
                                 line1, line2, labels, crossing,
                                 _known_pairs((f"v_{a1}", f"v_{point}/{a1}"), (f"v_{a2}", f"v_{point}/{a2}")),
                                 (_parallel(polygon, f"v_{point}/{a1}", t.first_slider, t.side1, point),
                                  _parallel(polygon, f"v_{point}/{a2}", t.second_slider, t.side2, point)))
        _slide_rel(polygon, t.first_slider, t.first_relative, point, sliding)
        _slide_rel(polygon, t.second_slider, j, point, sliding)
    sines[dyad.name] = crossing.sin_angle


def construct_velocity(positions: Positions, plan: PositionPlan, wanted: tuple[tuple[str, str], ...] = (), *,
                       unit: str = "mm", record: bool = False, strict: bool = False,
                       crossing: CrossLines = cross_lines) -> VelocityResult:
    """Construct the velocity polygon at every row for every group of ``plan``, then the tips of ``wanted``.

    ``wanted`` holds (link, point) pairs: the velocity of ``point`` as a point of ``link``.
    ``record``: keep the steps of row 0; ``strict``: a parallel pair of lines raises (a solve).
    """
    from kinepoly.engine.group import velocity_by_linear_solve

    polygon = Polygon(positions, "velocity", unit=unit, record=record, strict=strict, crossing=crossing)
    sliding: dict[str, Points] = {}
    sines: dict[str, Reals] = {}
    _drive(polygon, sliding)
    for group in plan.groups:
        if isinstance(group, Dyad):
            _dyad(polygon, group, sliding, sines)
        else:
            velocity_by_linear_solve(polygon, group, sliding)
    for link, point in wanted:
        polygon.tip(link, point)
    return VelocityResult(polygon, sliding, sines)
