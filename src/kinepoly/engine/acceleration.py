"""The acceleration polygon, constructed dyad by dyad after the velocity polygon, over rows.

Known terms are laid end to end (normal terms omega^2 r toward the center, Coriolis terms
2 omega x v_rel), then two direction lines are drawn (tangential: perpendicular to the link;
sliding: parallel to the slide) and their crossing is the unknown tip. Alpha is read off the
tangential term. A Coriolis term exists only where a block slides on a guide that can turn.

``Rules`` switch a construction mistake in (the homework checker's diagnoses): the normal term
laid away from the center, the Coriolis term left out or reversed. The right rules are the default.
"""

from __future__ import annotations

import math

import numpy as np

from kinepoly.engine.carry import relative_acceleration
from kinepoly.engine.closures import other_side
from kinepoly.engine.lines import add_motor_rate, lay_driven_slider, read_rate, record_drive_term, slide_direction
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
from kinepoly.engine.results import (
    RIGHT,
    AccelerationResult,
    Context,
    Rules,
    VelocityResult,
    along_normal,
    along_slide,
    normals_step,
    record_crossing,
    slide_label,
)
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.engine.velocity import carried_parts, drive_geometry
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import cross_lines
from kinepoly.model.mechanism import Revolute
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput, SliderSpec

__all__ = ["RIGHT", "AccelerationResult", "Rules", "construct_acceleration"]


def _dyad(ctx: Context, dyad: Dyad) -> None:
    b, i, j = ctx.b, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        k1 = other_side(dyad.first_joint, i)
        line1, n1, label1 = ctx.normal_line(k1, p1, p2, i)
        vectors = [n1] if n1 else []
        if isinstance(dyad.second_joint, Revolute):
            p3 = dyad.second_joint.point
            k2 = other_side(dyad.second_joint, j)
            line2, n2, label2 = ctx.normal_line(k2, p3, p2, j)
            vectors += [n2] if n2 else []
        else:
            k2 = other_side(dyad.second_joint, j)
            line2, laid = ctx.slide_line(dyad.second_joint, k2, j, p2)
            label2 = slide_label(dyad.second_joint)
            vectors += laid
        if b.record:
            normals_step(ctx, vectors)
        crossing = b.cross_lines(line1, line2, p2, dyad.name, (label1, label2))
        b.add_tip(i, p2, crossing.point)
        if b.record:
            direction1 = along_normal(ctx, f"a^t_{p2}/{p1}", k1, p1, p2, n1)
            if isinstance(dyad.second_joint, Revolute):
                p3 = dyad.second_joint.point
                direction2 = along_normal(ctx, f"a^t_{p2}/{p3}", k2, p3, p2, n2)
                equation = (f"a_{p2} = a_{p1} + a^n_{p2}/{p1} + a^t_{p2}/{p1} = a_{p3} + a^n_{p2}/{p3} + "
                            f"a^t_{p2}/{p3}")
            else:
                at2 = b.label(k2, p2)
                direction2 = along_slide(ctx, f"a_{p2}/{at2}", dyad.second_joint, k2, p2, laid)
                cor = f" + a^c_{p2}/{at2}" if laid else ""
                equation = f"a_{p2} = a_{p1} + a^n_{p2}/{p1} + a^t_{p2}/{p1} = a_{at2}{cor} + a_{p2}/{at2}"
            record_crossing(ctx, p2, equation, line1, line2, (label1, label2), crossing, vectors, (direction1, direction2))
        read_rate(b, i, p1, p2, crossing.along_first)
        if isinstance(dyad.second_joint, Revolute):
            read_rate(b, j, dyad.second_joint.point, p2, crossing.along_second())
        else:
            ctx.slide_values(dyad.second_joint, j, p2)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p = r.guide_pin, r.block_pin
        at = b.label(r.guide, p)
        line1, n1, label1 = ctx.normal_line(r.guide_known, q, p, r.guide, rigid=False, name=at)
        a_p = b.tip(r.block_known, p)
        end, laid = ctx.lay_coriolis(r.slider, a_p, r.guide, r.block, p)
        vectors = ([n1] if n1 else []) + laid
        line2 = (end, slide_direction(b.positions, r.slider), 1.0)
        labels = (label1, slide_label(r.slider))
        if b.record:
            normals_step(ctx, vectors)
        crossing = b.cross_lines(line1, line2, at, dyad.name, labels)
        b.add_tip(r.guide, p, crossing.point)
        if b.record:
            cor = f" + a^c_{at}/{p}" if laid else ""
            record_crossing(ctx, at, f"a_{at} = a_{q} + a^n_{at}/{q} + a^t_{at}/{q} = a_{p}{cor} + a_{at}/{p}", line1, line2,
                    labels, crossing, vectors,
                    (along_normal(ctx, f"a^t_{at}/{q}", r.guide_known, q, p, n1),
                     along_slide(ctx, f"a_{at}/{p}", r.slider, r.block_known, p, laid)))
        read_rate(b, r.guide, q, at, crossing.along_first)
        ctx.slide_values(r.slider, r.block, p)
    else:
        t = two_slide_roles(dyad, b.mechanism)
        if t.pin is not None and t.pin_known is not None:
            b.tip(t.pin_known, t.pin)
        point = t.point
        line1, v1 = ctx.slide_line(t.first_slider, t.side1, t.moving, point)
        line2, v2 = ctx.slide_line(t.second_slider, t.side2, j, point)
        labels = (slide_label(t.first_slider), slide_label(t.second_slider))
        crossing = b.cross_lines(line1, line2, point, dyad.name, labels)
        b.add_tip(t.moving, point, crossing.point)
        if b.record:
            a1, a2 = b.label(t.side1, point), b.label(t.side2, point)
            side_terms = ["".join(f" + {v.label}" for v in laid) for laid in (v1, v2)]
            record_crossing(ctx, point, f"a_{point} = a_{a1}{side_terms[0]} + a_{point}/{a1} = a_{a2}{side_terms[1]} + "
                    f"a_{point}/{a2}", line1, line2, labels, crossing, v1 + v2,
                    (along_slide(ctx, f"a_{point}/{a1}", t.first_slider, t.side1, point, v1),
                     along_slide(ctx, f"a_{point}/{a2}", t.second_slider, t.side2, point, v2)))
        ctx.slide_values(t.first_slider, t.first_relative, point)
        ctx.slide_values(t.second_slider, j, point)


def _drive(ctx: Context) -> None:
    mech = ctx.b.mechanism
    if isinstance(mech.scene.input, GivenInput):
        _given(ctx, mech.scene.input)
        return
    for drive in mech.drives:
        if drive.on_frame:
            _frame_drive(ctx, drive.spec)


def _frame_drive(ctx: Context, inp: LinkInput | SliderInput) -> None:
    b = ctx.b
    mech = b.mechanism
    if isinstance(inp, LinkInput):
        b.set_rate(inp.link, np.full(b.n, inp.alpha))
        if b.record:
            b.step(Step(polygon="acceleration", kind="known", equation=f"alpha{mech.ground}{inp.link} given",
                        result=f"alpha{mech.ground}{inp.link}", value=(inp.alpha,), topic="input-rate",
                        params=(("link", inp.link), ("ground", mech.ground or ""), ("rate", abs(inp.alpha)),
                                ("sense", sense(inp.alpha)))))
    else:
        slider = mech.slider(inp.slider)
        ctx.sliding[slider.name] = lay_driven_slider(b, slider, inp.s_ddot)
        ctx.coriolis[slider.name] = b.zero


def _drive_group(ctx: Context, group: DriveGroup) -> None:
    """A link placed on a known one by a driven joint: a motor adds its alpha; a cylinder's block point
    gets the Coriolis term 2 omega x s_dot e, then s_ddot along the slide."""
    b, drive = ctx.b, group.drive
    if isinstance(drive.joint, SliderSpec):
        slider = drive.joint
        start = b.tip(group.known, slider.point)
        moving = slider.block if group.known == slider.guide else slider.guide
        sign = 1.0 if moving == slider.block else -1.0
        end, _ = ctx.lay_coriolis(slider, start, slider.block, slider.guide, slider.point, sign)
        ctx.sliding[slider.name] = lay_driven_slider(b, slider, drive.rate(2), group.known, end)
        ctx.coriolis[slider.name] = np.asarray(sign * (end - start))
        return
    b.tip(group.known, drive.joint.point)
    known_rate = b.rate_of(group.known)
    assert known_rate is not None
    add_motor_rate(b, drive, group.link, group.known, known_rate)


def _carried(ctx: Context, dyad: Dyad) -> None:
    """A carried RRR dyad: the carrier's normal term and the drive's relative acceleration laid from the
    carrier's known tip, then the line perpendicular to the carrier's span; the second link as in any RRR."""
    b = ctx.b
    i, j, carrier, drive, (p1, p2, p3), (k1, k2) = carried_parts(dyad)
    at, pin, slide = drive_geometry(b, dyad)
    omega_i, omega_c = b.omega_of(i), b.omega_of(carrier)
    rel = relative_acceleration(drive, i, at, pin, slide, omega_i, omega_c, omega_c)
    on_carrier = b.label(carrier, p2)
    (start, direction, _), n1, label1 = ctx.normal_line(k1, p1, p2, carrier, rigid=False)
    if n1 is not None:
        n1 = DrawnVector(f"a^n_{on_carrier}/{p1}", n1.start, n1.end, "normal")
    moved = np.asarray(start + rel)
    line1: Line = (moved, direction, None)
    line2, n2, label2 = ctx.normal_line(k2, p3, p2, j)
    vectors = [v for v in (n1, n2) if v is not None]
    if b.record:
        normals_step(ctx, vectors)
        record_drive_term(b, drive, f"a_{p2}/{on_carrier}", start, moved, p2, carrier,
                          n1.label if n1 is not None else b.label(k1, p1).lower())
    crossing = b.cross_lines(line1, line2, p2, dyad.name, (label1, label2))
    b.add_tip(i, p2, crossing.point)
    b.add_tip(carrier, p2, np.asarray(crossing.point - rel))
    if b.record:
        drawn = vectors + [DrawnVector(f"a_{p2}/{on_carrier}", b.vec(start), b.vec(moved), "relative")]
        record_crossing(ctx, p2, f"a_{p2} = a_{p1} + a^n_{on_carrier}/{p1} + a_{p2}/{on_carrier} + a^t_{on_carrier}/{p1} = "
                f"a_{p3} + a^n_{p2}/{p3} + a^t_{p2}/{p3}", line1, line2, (label1, label2), crossing, drawn,
                (Direction(f"a^t_{on_carrier}/{p1}", "perpendicular", f"{p1}{p2}", b.label(k1, p1).lower(),
                           after=f"a_{p2}/{on_carrier}"),
                 along_normal(ctx, f"a^t_{p2}/{p3}", k2, p3, p2, n2)))
    read_rate(b, carrier, p1, on_carrier, crossing.along_first)
    if isinstance(drive.joint, Revolute):
        add_motor_rate(b, drive, i, carrier, crossing.along_first)
    else:
        assert slide is not None
        ctx.sliding[drive.joint.name] = np.asarray(drive.rate(2) * slide)
        ctx.coriolis[drive.joint.name] = np.asarray(2.0 * omega_c * (1j * drive.rate(1) * slide))
    read_rate(b, j, p3, p2, crossing.along_second())


def _given(ctx: Context, given: GivenInput) -> None:
    b = ctx.b
    link = b.mechanism.link_names[0]
    for g in given.points:
        assert g.acceleration is not None
        b.add_tip(link, g.name, np.full(b.n, complex(*g.acceleration)))
        if b.record:
            b.step(Step(polygon="acceleration", kind="known", equation=f"a_{g.name} given", result=g.name.lower(),
                        known=((f"a_{g.name}", "magnitude and direction"),),
                        vectors=(DrawnVector(f"a_{g.name}", (0.0, 0.0), g.acceleration, "absolute"),),
                        value=g.acceleration, topic="given-point",
                        params=(("point", g.name), ("magnitude", math.hypot(*g.acceleration)))))
    first, second = given.points[0], given.points[1]
    assert first.acceleration is not None and second.acceleration is not None
    r = complex(b.world(second.name)[0] - b.world(first.name)[0])
    w = b.num(b.omega_of(link))
    normal = -w * w * r
    a_first, a_second = complex(*first.acceleration), complex(*second.acceleration)
    rel = a_second - a_first
    along = r / abs(r)
    misfit = ((rel - normal) * along.conjugate()).real
    if abs(misfit) > 1e-9 * max(abs(a_first), abs(a_second), abs(normal), 1e-300):
        raise SceneError(f"{b.mechanism.scene.source}: given.{second.name}.acceleration: along "
                         f"{first.name}{second.name} the given accelerations differ by "
                         f"{(rel * along.conjugate()).real:.6g} {b.unit}, but a rigid body turning at omega = "
                         f"{w:.6g} rad/s needs {(normal * along.conjugate()).real:.6g} (off by {misfit:.6g})")
    middle = a_first + normal
    if b.record:
        b.step(Step(polygon="acceleration", kind="known", equation=f"a^n_{second.name}/{first.name}",
                    result=f"a^n_{second.name}/{first.name}",
                    vectors=(DrawnVector(f"a^n_{second.name}/{first.name}", first.acceleration,
                                         (middle.real, middle.imag), "normal"),
                             DrawnVector(f"a^t_{second.name}/{first.name}", (middle.real, middle.imag),
                                         second.acceleration, "tangential")),
                    topic="given-normal", params=(("point", second.name), ("reference", first.name),
                                                  ("magnitude", abs(normal)))))
    read_rate(b, link, first.name, second.name, np.full(b.n, ((a_second - middle) / (1j * r)).real))


def construct_acceleration(velocity: VelocityResult, plan: PositionPlan, wanted: tuple[tuple[str, str], ...] = (),
                           *, unit: str = "mm", record: bool = False, strict: bool = False, rules: Rules = RIGHT,
                           crossing: CrossLines = cross_lines) -> AccelerationResult:
    """Construct the acceleration polygon at every row for every group of ``plan``, on top of its velocity polygon."""
    positions = velocity.polygon.positions
    polygon = Polygon(positions, "acceleration", omega=velocity.omega, unit=unit, record=record, strict=strict,
                      crossing=crossing)
    polygon.normal_sign = rules.normal
    ctx = Context(polygon, velocity, rules)
    _drive(ctx)
    for group in plan.groups:
        if isinstance(group, Dyad) and group.carrier is not None:
            _carried(ctx, group)
        elif isinstance(group, Dyad):
            _dyad(ctx, group)
        elif isinstance(group, DriveGroup):
            _drive_group(ctx, group)
        else:
            _other_group(ctx, group)
    for link, point in wanted:
        polygon.tip(link, point)
    return AccelerationResult(polygon, ctx.sliding, ctx.coriolis)


def _other_group(ctx: Context, group: GearGroup | CamGroup | NewtonGroup) -> None:
    """A gear pair, a cam pair, a triad (through its Assur point) or any other group (a linear solve), by the
    modules that build on this one (imported here, where such a group is met)."""
    from kinepoly.engine.cam_polygons import acceleration_by_cam
    from kinepoly.engine.group import acceleration_by_linear_solve
    from kinepoly.engine.planet import planet_of
    from kinepoly.engine.rolling import acceleration_by_rolling, acceleration_of_planet
    from kinepoly.engine.triad import acceleration_by_assur_point, triad_of

    if isinstance(group, GearGroup):
        acceleration_by_rolling(ctx, group)
    elif isinstance(group, CamGroup):
        acceleration_by_cam(ctx, group)
    elif isinstance(group, NewtonGroup) and (planet := planet_of(group)) is not None:
        acceleration_of_planet(ctx, planet)
    elif (triad := triad_of(ctx.b.mechanism, group)) is not None:
        acceleration_by_assur_point(ctx, triad)
    else:
        acceleration_by_linear_solve(ctx, group)
