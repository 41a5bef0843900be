"""Direction lines of the velocity polygon and the steps that record them, for every group kind.

A line is drawn through a known tip: perpendicular to a link for a turning relative velocity, parallel
to a slide for a sliding one; where two cross is the unknown tip, and omega is read off the crossing
(``read_rate``). The steps say the same as data (``Direction``, ``Step``).
"""

from __future__ import annotations

import numpy as np

from kinepoly.engine.placement import Positions
from kinepoly.engine.polygon import Line, Polygon, sense
from kinepoly.engine.steps import Direction, DrawnVector, Relation, Step
from kinepoly.geom.arrays import Crossing, Points, Reals, turn
from kinepoly.geom.vec import magnitude
from kinepoly.model.mechanism import Drive, Mechanism
from kinepoly.scene.link_point import point_of
from kinepoly.scene.spec import SliderSpec

__all__ = ["add_motor_rate", "known_pairs", "lay_driven_slider", "link_length", "parallel", "parallel_label",
           "perpendicular", "perpendicular_label", "read_rate", "record_drive_term", "record_intersection",
           "revolute_line", "slide_direction", "slide_line", "slide_reference", "slide_rel"]


def slide_direction(positions: Positions, slider: SliderSpec) -> Points:
    """The unit direction of a slide at every row (it turns with the guide)."""
    return np.asarray(positions.poses[slider.guide].rotation * turn(slider.angle_rad))


def link_length(mechanism: Mechanism, link: str, a: str, b: str) -> float:
    """|ab| in ``link``'s own frame: the length of a direction k x ab drawn for that link."""
    return mechanism.distance(link, a, b)


def read_rate(polygon: Polygon, link: str, first: str, second: str, along: Reals) -> None:
    """Read omega (or alpha, from a tangential term) of ``link`` off the polygon, with its step.

    The crossing lies ``along`` direction vectors k x (first -> second) from the known tip, so the
    relative vector is along * (k x r): |term| / |r| = |along|, counter-clockwise when positive.
    """
    polygon.set_rate(link, along)
    if not polygon.record:
        return
    value = polygon.num(along)
    length = magnitude(complex(polygon.world(point_of(second))[0] - polygon.world(first)[0]))
    symbol = "omega" if polygon.kind == "velocity" else "alpha"
    term = f"v_{second}/{first}" if polygon.kind == "velocity" else f"a^t_{second}/{first}"
    ground = polygon.ground_name()
    polygon.step(Step(polygon=polygon.kind, kind="read", equation=f"{symbol}{ground}{link} = "
                                                                  f"|{term}| / |{first}{second}|",
                      result=f"{symbol}{ground}{link}", value=(value,), topic="read",
                      params=(("link", link), ("ground", ground), ("term", term), ("first", first),
                              ("second", second), ("magnitude", abs(value) * length), ("length", length),
                              ("rate", abs(value)), ("sense", sense(value)))))


def lay_driven_slider(polygon: Polygon, slider: SliderSpec, amount: float, known: str | None = None,
                      start: Points | None = None) -> Points:
    """The tip of a driven slider's point: ``amount`` (s_dot or s_ddot) along the slide, from the tip
    ``start`` of the point on the ``known`` side (by default the frame's side, from o).

    Returns the block's motion relative to the guide, ``amount`` along the slide.
    """
    rel = np.asarray(amount * slide_direction(polygon.positions, slider))
    known = known if known is not None else polygon.mechanism.ground
    moving = slider.block if slider.guide == known else slider.guide
    origin = polygon.zero if start is None else start
    value = np.asarray(origin + (rel if moving == slider.block else -rel))
    label = polygon.add_tip(moving, slider.point, value)
    if polygon.record:
        name = "s_dot" if polygon.kind == "velocity" else "s_ddot"
        symbol = polygon.symbol
        term = f"{symbol}_{label}" if start is None or known is None else (
            f"{symbol}_{label}/{polygon.label(known, slider.point)}")
        polygon.step(Step(polygon=polygon.kind, kind="known",
                          equation=f"{term} = {name}{slider.name} along the slide", result=label.lower(),
                          known=((term, "magnitude and direction"),),
                          vectors=(DrawnVector(term, polygon.vec(origin), polygon.vec(value),
                                               "absolute" if start is None else "relative"),),
                          value=polygon.vec(value), topic="driven-slider",
                          params=(("slider", slider.name), ("point", label), ("amount", amount))))
    return rel


def revolute_line(polygon: Polygon, known_link: str, known_point: str, point: str, link: str | None) -> Line:
    """Through the tip of known_point, perpendicular to known_point -> point (both points of ``link``,
    when given, so that the direction's length is that link's)."""
    start = polygon.tip(known_link, known_point)
    size = None if link is None else link_length(polygon.mechanism, link, known_point, point)
    return start, polygon.positions.chord(known_point, point)[1], size


def perpendicular(polygon: Polygon, term: str, known_link: str, known_point: str, point: str) -> Direction:
    """What ``revolute_line`` draws, as data."""
    return Direction(term, "perpendicular", f"{known_point}{point}", polygon.label(known_link, known_point).lower())


def slide_reference(polygon: Polygon, slider: SliderSpec) -> tuple[Relation, str]:
    """What a line along ``slider`` is parallel to, as a step says it: the slide of the slider, or the flat face
    of the follower where the slider is a cam's equivalent block (the block at K on the face)."""
    if slider.block in polygon.mechanism.scene.equivalent_links:
        return "face", slider.guide
    return "parallel", slider.name


def parallel(polygon: Polygon, term: str, slider: SliderSpec, other: str, point: str) -> Direction:
    """What ``slide_line`` draws, as data."""
    return Direction(term, *slide_reference(polygon, slider), polygon.label(other, point).lower())


def slide_line(polygon: Polygon, slider: SliderSpec, other: str, point: str) -> Line:
    """Through the tip of point@other, parallel to the slide (a unit direction)."""
    return polygon.tip(other, point), slide_direction(polygon.positions, slider), 1.0


def perpendicular_label(polygon: Polygon, known_link: str, known_point: str, point: str) -> str:
    return f"perpendicular to {known_point}{point} through {polygon.label(known_link, known_point).lower()}"


def parallel_label(slider: SliderSpec, through: str) -> str:
    return f"parallel to slider {slider.name} through {through.lower()}"


def record_intersection(polygon: Polygon, label: str, equation: str, first: Line, second: Line,
                         line_labels: tuple[str, str], crossing: Crossing, known: tuple[tuple[str, str], ...],
                         directions: tuple[Direction, Direction], vectors: tuple[DrawnVector, ...] = ()) -> None:
    polygon.step(Step(polygon="velocity", kind="intersection", equation=equation, result=label.lower(), known=known,
                      vectors=vectors,
                      lines=(polygon.step_line(first, line_labels[0]), polygon.step_line(second, line_labels[1])),
                      value=polygon.vec(crossing.point), topic="intersection", params=(("point", label),),
                      directions=directions))


def slide_rel(polygon: Polygon, slider: SliderSpec, link: str, point: str, sliding: dict[str, Points]) -> None:
    """Velocity of the block relative to the guide, from the tips of ``point`` on both sides."""
    other = slider.guide if link == slider.block else slider.block
    on_link = polygon.tips[polygon.label(link, point)]
    on_other = polygon.tip(other, point)
    sliding[slider.name] = np.asarray(on_link - on_other if link == slider.block else on_other - on_link)


def known_pairs(*terms: tuple[str, str]) -> tuple[tuple[str, str], ...]:
    """(term, what is known of it) for the four terms of a dyad's equation: known, direction, known, direction."""
    return tuple((term, "magnitude and direction" if k % 2 == 0 else "direction") for k, term in
                 enumerate(t for pair in terms for t in pair))


def add_motor_rate(polygon: Polygon, drive: Drive, link: str, known: str, known_rate: Reals) -> None:
    """``link``'s rate (omega or alpha, as the polygon is) as ``known``'s plus the motor's, with its step."""
    sign = 1.0 if link == drive.moving else -1.0
    polygon.set_rate(link, np.asarray(known_rate + sign * drive.rate(1 if polygon.kind == "velocity" else 2)))
    if not polygon.record:
        return
    symbol = "omega" if polygon.kind == "velocity" else "alpha"
    ground = polygon.ground_name()
    value = polygon.num(polygon.rate[link])
    moving, base = drive.moving, drive.base
    sign_text = "+" if sign > 0 else "-"
    polygon.step(Step(polygon=polygon.kind, kind="known",
                      equation=f"{symbol}{ground}{link} = {symbol}{ground}{known} {sign_text} {symbol}{base}{moving}",
                      result=f"{symbol}{ground}{link}", value=(value,), topic="added-rate",
                      params=(("link", link), ("known", known), ("ground", ground), ("motor", f"{base}{moving}"),
                              ("sign", sign_text), ("rate", abs(value)), ("sense", sense(value)))))


def record_drive_term(polygon: Polygon, drive: Drive, term: str, start: Points, end: Points, point: str,
                      carrier: str, after: str) -> None:
    """The known step of a driven joint's relative term (velocity or acceleration), laid from ``start``
    (the tip or the end of the term named ``after``)."""
    polygon.step(Step(polygon=polygon.kind, kind="known", equation=f"{term} from {drive.name}", result=term,
                      known=((term, "magnitude and direction"),),
                      vectors=(DrawnVector(term, polygon.vec(start), polygon.vec(end), "relative"),),
                      value=polygon.vec(np.asarray(end - start)), topic="drive-term",
                      params=(("term", term), ("drive", drive.name), ("point", point), ("carrier", carrier),
                              ("after", after), ("magnitude", magnitude(complex(end[0]) - complex(start[0]))))))
