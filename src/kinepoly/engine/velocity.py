"""The velocity polygon, constructed dyad by dyad by crossing two direction lines, over rows.

For each dyad the unknown tip is where two lines through known tips cross: perpendicular to
the link for a turning relative velocity (v_B/A is perpendicular to AB), parallel to the slide
for a sliding one. Omega of a link is then read off the polygon, |v_B/A| / |AB| with the sense
of v_B/A: the line through a along k x AB meets the other at a + t (k x AB), so omega = t, the
crossing's ``along`` (``read_rate``).
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.engine.carry import relative_velocity
from kinepoly.engine.closures import other_side
from kinepoly.engine.contacts import record_equivalent_links
from kinepoly.engine.lines import (
    add_motor_rate,
    known_pairs,
    lay_driven_slider,
    link_length,
    parallel,
    parallel_label,
    perpendicular,
    perpendicular_label,
    read_rate,
    record_drive_term,
    record_intersection,
    revolute_line,
    slide_direction,
    slide_line,
    slide_reference,
    slide_rel,
)
from kinepoly.engine.plan import (
    CamGroup,
    DriveGroup,
    Dyad,
    GearGroup,
    NewtonGroup,
    PositionPlan,
    slide_roles,
    two_slide_roles,
)
from kinepoly.engine.polygon import CrossLines, Line, Polygon, sense
from kinepoly.engine.position import Positions
from kinepoly.engine.results import VelocityResult
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import Points, Reals, cross_lines
from kinepoly.model.mechanism import Drive, Revolute
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput, SliderSpec

__all__ = ["VelocityResult", "construct_velocity", "link_length", "read_rate", "slide_direction", "slide_reference"]


def _drive(polygon: Polygon, sliding: dict[str, Points]) -> None:
    mech = polygon.mechanism
    if isinstance(mech.scene.input, GivenInput):
        _given(polygon, mech.scene.input)
        return
    for drive in mech.drives:
        if drive.on_frame:
            _frame_drive(polygon, drive.spec, sliding)


def _frame_drive(polygon: Polygon, inp: LinkInput | SliderInput, sliding: dict[str, Points]) -> None:
    mech = polygon.mechanism
    if isinstance(inp, LinkInput):
        polygon.set_rate(inp.link, np.full(polygon.n, inp.omega))
        if polygon.record:
            polygon.step(Step(polygon="velocity", kind="known", equation=f"omega{mech.ground}{inp.link} given",
                              result=f"omega{mech.ground}{inp.link}", value=(inp.omega,), topic="input-rate",
                              params=(("link", inp.link), ("ground", mech.ground or ""), ("rate", abs(inp.omega)),
                                      ("sense", sense(inp.omega)))))
    else:
        slider = mech.slider(inp.slider)
        sliding[slider.name] = lay_driven_slider(polygon, slider, inp.s_dot)


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


def _dyad(polygon: Polygon, dyad: Dyad, sliding: dict[str, Points], sines: dict[str, Reals]) -> None:
    mech, i, j = polygon.mechanism, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        k1 = other_side(dyad.first_joint, i)
        line1 = revolute_line(polygon, k1, p1, p2, i)
        label1 = perpendicular_label(polygon, k1, p1, p2)
        if isinstance(dyad.second_joint, Revolute):
            p3 = dyad.second_joint.point
            k2 = other_side(dyad.second_joint, j)
            line2 = revolute_line(polygon, k2, p3, p2, j)
            label2 = perpendicular_label(polygon, k2, p3, p2)
        else:
            k2 = other_side(dyad.second_joint, j)
            line2 = slide_line(polygon, dyad.second_joint, k2, p2)
            label2 = parallel_label(dyad.second_joint, polygon.label(k2, p2))
        crossing = polygon.cross_lines(line1, line2, p2, dyad.name, (label1, label2))
        polygon.add_tip(i, p2, crossing.point)
        if polygon.record:
            direction1 = perpendicular(polygon, f"v_{p2}/{p1}", k1, p1, p2)
            if isinstance(dyad.second_joint, Revolute):
                p3 = dyad.second_joint.point
                direction2 = perpendicular(polygon, f"v_{p2}/{p3}", k2, p3, p2)
                equation = f"v_{p2} = v_{p1} + v_{p2}/{p1} = v_{p3} + v_{p2}/{p3}"
                known = known_pairs((f"v_{p1}", f"v_{p2}/{p1}"), (f"v_{p3}", f"v_{p2}/{p3}"))
            else:
                at2 = polygon.label(k2, p2)
                direction2 = parallel(polygon, f"v_{p2}/{at2}", dyad.second_joint, k2, p2)
                equation = f"v_{p2} = v_{p1} + v_{p2}/{p1} = v_{at2} + v_{p2}/{at2}"
                known = known_pairs((f"v_{p1}", f"v_{p2}/{p1}"), (f"v_{at2}", f"v_{p2}/{at2}"))
            record_intersection(polygon, p2, equation, line1, line2, (label1, label2), crossing, known,
                                 (direction1, direction2))
        read_rate(polygon, i, p1, p2, crossing.along_first)
        if isinstance(dyad.second_joint, Revolute):
            read_rate(polygon, j, dyad.second_joint.point, p2, crossing.along_second())
        else:
            slide_rel(polygon, dyad.second_joint, j, p2, sliding)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p = r.guide_pin, r.block_pin
        line1 = revolute_line(polygon, r.guide_known, q, p, None)
        start = polygon.tip(r.block_known, p)
        line2 = (start, slide_direction(polygon.positions, r.slider), 1.0)
        at = polygon.label(r.guide, p)
        labels = (perpendicular_label(polygon, r.guide_known, q, p), parallel_label(r.slider, p))
        crossing = polygon.cross_lines(line1, line2, at, dyad.name, labels)
        polygon.add_tip(r.guide, p, crossing.point)
        if polygon.record:
            record_intersection(polygon, at, f"v_{at} = v_{q} + v_{at}/{q} = v_{p} + v_{at}/{p}", line1, line2,
                                 labels, crossing, known_pairs((f"v_{q}", f"v_{at}/{q}"), (f"v_{p}", f"v_{at}/{p}")),
                                 (perpendicular(polygon, f"v_{at}/{q}", r.guide_known, q, p),
                                  parallel(polygon, f"v_{at}/{p}", r.slider, r.block_known, p)))
        read_rate(polygon, r.guide, q, at, crossing.along_first)
        sliding[r.slider.name] = np.asarray(start - crossing.point)
    else:  # PRP and RPP: both links' omegas are known from their guides, two slide lines cross
        t = two_slide_roles(dyad, mech)
        if t.pin is not None and t.pin_known is not None:
            polygon.tip(t.pin_known, t.pin)
        point = t.point
        line1 = slide_line(polygon, t.first_slider, t.side1, point)
        line2 = slide_line(polygon, t.second_slider, t.side2, point)
        a1, a2 = polygon.label(t.side1, point), polygon.label(t.side2, point)
        labels = (parallel_label(t.first_slider, a1), parallel_label(t.second_slider, a2))
        crossing = polygon.cross_lines(line1, line2, point, dyad.name, labels)
        polygon.add_tip(t.moving, point, crossing.point)
        if polygon.record:
            record_intersection(polygon, point, f"v_{point} = v_{a1} + v_{point}/{a1} = v_{a2} + v_{point}/{a2}",
                                 line1, line2, labels, crossing,
                                 known_pairs((f"v_{a1}", f"v_{point}/{a1}"), (f"v_{a2}", f"v_{point}/{a2}")),
                                 (parallel(polygon, f"v_{point}/{a1}", t.first_slider, t.side1, point),
                                  parallel(polygon, f"v_{point}/{a2}", t.second_slider, t.side2, point)))
        slide_rel(polygon, t.first_slider, t.first_relative, point, sliding)
        slide_rel(polygon, t.second_slider, j, point, sliding)
    sines[dyad.name] = crossing.sin_angle


def _drive_group(polygon: Polygon, group: DriveGroup, sliding: dict[str, Points]) -> None:
    """A link placed on a known one by a driven joint: a motor adds its omega, a cylinder its s_dot."""
    drive = group.drive
    if isinstance(drive.joint, SliderSpec):
        slider = drive.joint
        start = polygon.tip(group.known, slider.point)
        sliding[slider.name] = lay_driven_slider(polygon, slider, drive.rate(1), group.known, start)
        return
    polygon.tip(group.known, drive.joint.point)
    known_rate = polygon.rate_of(group.known)
    assert known_rate is not None
    add_motor_rate(polygon, drive, group.link, group.known, known_rate)


def carried_parts(dyad: Dyad) -> tuple[str, str, str, Drive, tuple[str, str, str], tuple[str, str]]:
    """A carried RRR dyad's links (first, second, carrier), its drive, its three pins (the carrier's known
    one, the inner one, the second link's known one) and the known links across the two outer pins."""
    carrier, drive = dyad.carrier, dyad.drive
    assert carrier is not None and drive is not None
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
    assert isinstance(dyad.second_joint, Revolute)
    pins = (dyad.first_joint.point, dyad.inner.point, dyad.second_joint.point)
    return (dyad.first, dyad.second, carrier, drive, pins,
            (other_side(dyad.first_joint, carrier), other_side(dyad.second_joint, dyad.second)))


def drive_geometry(polygon: Polygon, dyad: Dyad) -> tuple[Points, Points | None, Points | None]:
    """For a carried dyad: where its inner joint is, the motor's pin (or None), the slide's direction (or None)."""
    drive = dyad.drive
    assert drive is not None and isinstance(dyad.inner, Revolute)
    at = polygon.world(dyad.inner.point)
    if isinstance(drive.joint, Revolute):
        return at, polygon.world(drive.joint.point), None
    return at, None, slide_direction(polygon.positions, drive.joint)


def _carried(polygon: Polygon, dyad: Dyad, sliding: dict[str, Points], sines: dict[str, Reals]) -> None:
    """A carried RRR dyad: the drive's relative velocity is laid from the carrier's known tip, then the
    line perpendicular to the carrier's span; the second link's line as in any RRR dyad."""
    i, j, carrier, drive, (p1, p2, p3), (k1, k2) = carried_parts(dyad)
    at, pin, slide = drive_geometry(polygon, dyad)
    rel = relative_velocity(drive, i, at, pin, slide)
    start = polygon.tip(k1, p1)
    moved = np.asarray(start + rel)
    on_carrier = polygon.label(carrier, p2)
    line1: Line = (moved, np.asarray(1j * (at - polygon.world(p1))), None)
    line2 = revolute_line(polygon, k2, p3, p2, j)
    labels = (perpendicular_label(polygon, k1, p1, p2), perpendicular_label(polygon, k2, p3, p2))
    if polygon.record:
        record_drive_term(polygon, drive, f"v_{p2}/{on_carrier}", start, moved, p2, carrier,
                          polygon.label(k1, p1).lower())
    crossing = polygon.cross_lines(line1, line2, p2, dyad.name, labels)
    polygon.add_tip(i, p2, crossing.point)
    polygon.add_tip(carrier, p2, np.asarray(crossing.point - rel))
    if polygon.record:
        record_intersection(polygon, p2, f"v_{p2} = v_{p1} + v_{p2}/{on_carrier} + v_{on_carrier}/{p1} = v_{p3} + "
                             f"v_{p2}/{p3}", line1, line2, labels, crossing,
                             ((f"v_{p1}", "magnitude and direction"), (f"v_{p2}/{on_carrier}", "magnitude and direction"),
                              (f"v_{on_carrier}/{p1}", "direction"), (f"v_{p3}", "magnitude and direction"),
                              (f"v_{p2}/{p3}", "direction")),
                             (Direction(f"v_{on_carrier}/{p1}", "perpendicular", f"{p1}{p2}",
                                        polygon.label(k1, p1).lower(), after=f"v_{p2}/{on_carrier}"),
                              perpendicular(polygon, f"v_{p2}/{p3}", k2, p3, p2)),
                             (DrawnVector(f"v_{p2}/{on_carrier}", polygon.vec(start), polygon.vec(moved), "relative"),))
    read_rate(polygon, carrier, p1, on_carrier, crossing.along_first)
    if isinstance(drive.joint, Revolute):
        add_motor_rate(polygon, drive, i, carrier, crossing.along_first)
    else:
        sliding[drive.joint.name] = np.asarray(drive.rate(1) * slide_direction(polygon.positions, drive.joint))
    read_rate(polygon, j, p3, p2, crossing.along_second())
    sines[dyad.name] = crossing.sin_angle


def construct_velocity(positions: Positions, plan: PositionPlan, wanted: tuple[tuple[str, str], ...] = (), *,
                       unit: str = "mm", record: bool = False, strict: bool = False,
                       crossing: CrossLines = cross_lines) -> VelocityResult:
    """Construct the velocity polygon at every row for every group of ``plan``, then the tips of ``wanted``.

    ``wanted`` holds (link, point) pairs: the velocity of ``point`` as a point of ``link``.
    ``record``: keep the steps of row 0; ``strict``: a parallel pair of lines raises (a solve).
    """
    polygon = Polygon(positions, "velocity", unit=unit, record=record, strict=strict, crossing=crossing)
    sliding: dict[str, Points] = {}
    sines: dict[str, Reals] = {}
    equivalent: dict[str, Points] = {}
    _drive(polygon, sliding)
    record_equivalent_links(polygon)
    for group in plan.groups:
        if isinstance(group, Dyad) and group.carrier is not None:
            _carried(polygon, group, sliding, sines)
        elif isinstance(group, Dyad):
            _dyad(polygon, group, sliding, sines)
        elif isinstance(group, DriveGroup):
            _drive_group(polygon, group, sliding)
        else:
            _other_group(polygon, group, sliding, equivalent)
    for link, point in wanted:
        polygon.tip(link, point)
    return VelocityResult(polygon, sliding, sines, equivalent)


def _other_group(polygon: Polygon, group: GearGroup | CamGroup | NewtonGroup, sliding: dict[str, Points], equivalent: dict[str, Points]) -> None:
    """A gear pair, a cam pair, a triad (through its Assur point) or any other group (a linear solve), by the
    modules that build on this one (imported here, where such a group is met)."""
    from kinepoly.engine.cam_polygons import velocity_by_cam
    from kinepoly.engine.group import velocity_by_linear_solve
    from kinepoly.engine.planet import planet_of
    from kinepoly.engine.rolling import velocity_by_rolling, velocity_of_planet
    from kinepoly.engine.triad import triad_of, velocity_by_assur_point

    if isinstance(group, GearGroup):
        velocity_by_rolling(polygon, group, sliding)
    elif isinstance(group, CamGroup):
        velocity_by_cam(polygon, group, sliding, equivalent)
    elif isinstance(group, NewtonGroup) and (planet := planet_of(group)) is not None:
        velocity_of_planet(polygon, planet)
    elif (triad := triad_of(polygon.mechanism, group)) is not None:
        velocity_by_assur_point(polygon, triad, sliding, equivalent)
    else:
        velocity_by_linear_solve(polygon, group, sliding)
