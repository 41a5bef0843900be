"""The acceleration polygon, constructed dyad by dyad after the velocity polygon.

Known terms are laid end to end (normal terms omega^2 r toward the center, Coriolis terms
2 omega x v_rel), then two direction lines are drawn (tangential: perpendicular to the link;
sliding: parallel to the slide) and their crossing is the unknown tip. Alpha is read off the
tangential term. A Coriolis step exists only where a block slides on a guide that can turn.
"""

from __future__ import annotations

from dataclasses import dataclass

from kinepoly.construct.builder import Crossing, PolygonBuilder, sense
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.construct.velocity import VelocityPolygon, read_rate, slide_direction
from kinepoly.errors import SceneError
from kinepoly.geom import Line, intersect
from kinepoly.geom.vec import Vec, add, dot, norm, perp, scale, sub, unit
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.notice import Notice
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput, SliderSpec
from kinepoly.engine.plan import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.model.pose import Pose
from kinepoly.solve.position import describe_input

__all__ = ["AccelerationPolygon", "construct_acceleration"]


@dataclass(frozen=True)
class AccelerationPolygon:
    """Tips (physical accelerations, pole at 0), alphas, sliding accelerations, Coriolis terms, steps."""

    tips: dict[str, Vec]
    alpha: dict[str, float]
    sliding: dict[str, Vec]
    coriolis: dict[str, Vec]
    steps: tuple[Step, ...]
    notices: tuple[Notice, ...]
    members: dict[str, list[tuple[str, Vec]]]


class _Context:
    def __init__(self, builder: PolygonBuilder, velocity: VelocityPolygon) -> None:
        self.b = builder
        self.v = velocity
        self.sliding: dict[str, Vec] = {}
        self.coriolis: dict[str, Vec] = {}

    def v_tip(self, link: str, point: str) -> Vec:
        label = self.b.label(link, point)
        if link == self.b.mechanism.ground:
            return (0.0, 0.0)
        return self.v.tips[label]

    def normal_line(self, known_link: str, known_point: str, point: str, moving: str) -> tuple[Line, DrawnVector]:
        """Locus of a_point: a_known + a^n (toward known_point), then perpendicular to known_point -> point."""
        b = self.b
        start = b.tip(known_link, known_point)
        r = sub(b.world(point), b.world(known_point))
        w = b.omega_of(moving)
        normal = scale(-w * w, r)
        end = add(start, normal)
        vec = DrawnVector(f"a^n_{point}/{known_point}", start, end, "normal")
        return Line(end, perp(r), f"a^t_{point}/{known_point} perpendicular to {known_point}{point}"), vec

    def slide_line(self, slider: SliderSpec, other: str, moving: str, point: str) -> tuple[Line, list[DrawnVector]]:
        """Locus of a_point (point of ``moving``): a_point@other + Coriolis, then along the slide."""
        b = self.b
        start = b.tip(other, point)
        e = slide_direction(b.pose, slider)
        coriolis = self.lay_coriolis(slider, start, moving, other, point)
        vectors = [coriolis] if coriolis else []
        end = coriolis.end if coriolis else start
        return Line(end, e, f"sliding term along slider {slider.name}"), vectors

    def lay_coriolis(self, slider: SliderSpec, start: Vec, moving: str, frame: str, point: str) -> DrawnVector | None:
        """Lay 2 omega_frame x v_{point of moving}/{point of frame} from ``start``, with its step.

        None where the slider's guide cannot turn: then there is no Coriolis term at all.
        """
        b = self.b
        if not b.mechanism.has_turning_guide(slider):
            return None
        w = b.omega_of(frame)
        on_moving, on_frame = b.label(moving, point), b.label(frame, point)
        v_rel = sub(self.v_tip(moving, point), self.v_tip(frame, point))
        term = scale(2.0 * w, perp(v_rel))
        label = f"a^c_{on_moving}/{on_frame}"
        vector = DrawnVector(label, start, add(start, term), "coriolis")
        b.steps.append(Step("acceleration", "coriolis", f"{label} = 2 omega x v_{on_moving}/{on_frame}",
                            f"Coriolis term {label} = 2 omega{b.mechanism.ground}{slider.guide} x v_{on_moving}/{on_frame}: "
                            f"|{label}| = 2 x {abs(w):.6g} x {norm(v_rel):.6g} = {norm(term):.6g} {b.unit}; its "
                            f"direction is the relative velocity turned 90 deg in the sense of omega ({sense(w)}), "
                            f"laid from the tip of a_{on_frame}.", label, ((label, "magnitude and direction"),),
                            (vector,), value=term, topic="coriolis",
                            params=(("term", label), ("guide", slider.guide), ("ground", b.mechanism.ground or ""),
                                    ("omega", abs(w)), ("relative", f"v_{on_moving}/{on_frame}"),
                                    ("speed", norm(v_rel)), ("magnitude", norm(term)), ("sense", sense(w)),
                                    ("start", on_frame))))
        return vector

    def slide_values(self, slider: SliderSpec, link: str, point: str) -> None:
        """Sliding acceleration and Coriolis term of the block relative to the guide."""
        b = self.b
        other = slider.guide if link == slider.block else slider.block
        block_side, guide_side = (link, other) if link == slider.block else (other, link)
        a_block, a_guide = b.tip(block_side, point), b.tip(guide_side, point)
        v_rel = sub(self.v_tip(block_side, point), self.v_tip(guide_side, point))
        cor = scale(2.0 * b.omega_of(slider.guide), perp(v_rel))
        self.coriolis[slider.name] = cor
        self.sliding[slider.name] = sub(sub(a_block, a_guide), cor)


def _other(joint: Revolute | SliderSpec, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _record(ctx: _Context, label: str, equation: str, first: Line, second: Line, value: Vec,
            vectors: list[DrawnVector], known: tuple[tuple[str, str], ...],
            directions: tuple[Direction, Direction]) -> None:
    text = (f"Lay the known terms end to end, then draw {first.label} and {second.label}; they cross at "
            f"{label.lower()}: o{label.lower()} is a_{label} = ({value[0]:.6g}, {value[1]:.6g}) {ctx.b.unit}.")
    known = known + tuple((d.term, "direction") for d in directions)  # the two unknown terms
    ctx.b.steps.append(Step("acceleration", "intersection", equation, text, label.lower(), known,
                            tuple(vectors), (first, second), value=value, topic="intersection",
                            params=(("point", label),), directions=directions))


def _along_normal(ctx: _Context, term: str, known_link: str, known_point: str, point: str,
                  normal: DrawnVector) -> Direction:
    """What ``normal_line`` draws, as data: the tangential term, after the normal one."""
    return Direction(term, "perpendicular", f"{known_point}{point}", ctx.b.label(known_link, known_point).lower(),
                     after=normal.label)


def _along_slide(ctx: _Context, term: str, slider: SliderSpec, other: str, point: str,
                 laid: list[DrawnVector]) -> Direction:
    """What ``slide_line`` draws, as data: the sliding term, after the Coriolis term when there is one."""
    return Direction(term, "parallel", slider.name, ctx.b.label(other, point).lower(),
                     after=laid[-1].label if laid else "")


def _normals_step(ctx: _Context, vectors: list[DrawnVector]) -> None:
    normals = [v for v in vectors if v.term == "normal"]
    if normals:
        text = "; ".join(f"{v.label} = omega^2 r = {norm(sub(v.end, v.start)):.6g} {ctx.b.unit}, toward the center"
                         for v in normals)
        ctx.b.steps.append(Step("acceleration", "known", " and ".join(v.label for v in normals),
                                f"Lay the normal terms from the velocity polygon: {text}.",
                                ", ".join(v.label for v in normals),
                                tuple((v.label, "magnitude and direction") for v in normals), tuple(normals),
                                topic="normals"))


def _tangential(ctx: _Context, link: str, first: str, second: str, line: Line, value: Vec) -> None:
    at = sub(ctx.b.world(second), ctx.b.world(first))
    read_rate(ctx.b, link, first, second, sub(value, line.through), at)


def _dyad(ctx: _Context, dyad: Dyad, where: str) -> None:
    b, i, j = ctx.b, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        line1, n1 = ctx.normal_line(_other(dyad.first_joint, i), p1, p2, i)
        direction1 = _along_normal(ctx, f"a^t_{p2}/{p1}", _other(dyad.first_joint, i), p1, p2, n1)
        vectors = [n1]
        if isinstance(dyad.second_joint, Revolute):
            p3 = dyad.second_joint.point
            line2, n2 = ctx.normal_line(_other(dyad.second_joint, j), p3, p2, j)
            direction2 = _along_normal(ctx, f"a^t_{p2}/{p3}", _other(dyad.second_joint, j), p3, p2, n2)
            vectors.append(n2)
            equation = f"a_{p2} = a_{p1} + a^n_{p2}/{p1} + a^t_{p2}/{p1} = a_{p3} + a^n_{p2}/{p3} + a^t_{p2}/{p3}"
        else:
            k2 = _other(dyad.second_joint, j)
            line2, cv = ctx.slide_line(dyad.second_joint, k2, j, p2)
            vectors += cv
            at2 = b.label(k2, p2)
            direction2 = _along_slide(ctx, f"a_{p2}/{at2}", dyad.second_joint, k2, p2, cv)
            cor = f" + a^c_{p2}/{at2}" if cv else ""
            equation = f"a_{p2} = a_{p1} + a^n_{p2}/{p1} + a^t_{p2}/{p1} = a_{at2}{cor} + a_{p2}/{at2}"
        _normals_step(ctx, vectors)
        value = b.cross_lines(line1, line2, p2, where)
        b.add_tip(i, p2, value)
        _record(ctx, p2, equation, line1, line2, value, vectors,
                tuple((v.label, "magnitude and direction") for v in vectors), (direction1, direction2))
        _tangential(ctx, i, p1, p2, line1, value)
        if isinstance(dyad.second_joint, Revolute):
            _tangential(ctx, j, dyad.second_joint.point, p2, line2, value)
        else:
            ctx.slide_values(dyad.second_joint, j, p2)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p = r.guide_pin, r.block_pin
        line1, n1 = ctx.normal_line(r.guide_known, q, p, r.guide)
        a_p = b.tip(r.block_known, p)
        at = b.label(r.guide, p)
        coriolis = ctx.lay_coriolis(r.slider, a_p, r.guide, r.block, p)
        vectors = [n1, coriolis] if coriolis else [n1]
        end = coriolis.end if coriolis else a_p
        line2 = Line(end, slide_direction(b.pose, r.slider), f"sliding term along slider {r.slider.name}")
        _normals_step(ctx, vectors)
        value = b.cross_lines(line1, line2, at, where)
        b.add_tip(r.guide, p, value)
        cor = f" + a^c_{at}/{p}" if len(vectors) > 1 else ""
        _record(ctx, at, f"a_{at} = a_{q} + a^n_{at}/{q} + a^t_{at}/{q} = a_{p}{cor} + a_{at}/{p}", line1, line2,
                value, vectors, tuple((v.label, "magnitude and direction") for v in vectors),
                (_along_normal(ctx, f"a^t_{at}/{q}", r.guide_known, q, p, n1),
                 _along_slide(ctx, f"a_{at}/{p}", r.slider, r.block_known, p, vectors[1:])))
        _tangential(ctx, r.guide, q, p, line1, value)
        ctx.slide_values(r.slider, r.block, p)
    else:
        t = two_slide_roles(dyad, b.mechanism)
        if t.pin is not None and t.pin_known is not None:
            b.tip(t.pin_known, t.pin)
        point = t.point
        line1, v1 = ctx.slide_line(t.first_slider, t.side1, t.moving, point)
        line2, v2 = ctx.slide_line(t.second_slider, t.side2, j, point)
        value = b.cross_lines(line1, line2, point, where)
        b.add_tip(t.moving, point, value)
        a1, a2 = b.label(t.side1, point), b.label(t.side2, point)
        side_terms = ["".join(f" + {v.label}" for v in laid) for laid in (v1, v2)]
        _record(ctx, point, f"a_{point} = a_{a1}{side_terms[0]} + a_{point}/{a1} = a_{a2}{side_terms[1]} + "
                f"a_{point}/{a2}", line1, line2, value, v1 + v2, tuple((v.label, "magnitude and direction") for v in v1 + v2),
                (_along_slide(ctx, f"a_{point}/{a1}", t.first_slider, t.side1, point, v1),
                 _along_slide(ctx, f"a_{point}/{a2}", t.second_slider, t.side2, point, v2)))
        ctx.slide_values(t.first_slider, t.first_relative, point)
        ctx.slide_values(t.second_slider, j, point)


def _drive(ctx: _Context) -> None:
    b = ctx.b
    mech = b.mechanism
    inp = mech.scene.input
    if isinstance(inp, LinkInput):
        b.set_rate(inp.link, inp.alpha)
        b.steps.append(Step("acceleration", "known", f"alpha{mech.ground}{inp.link} given",
                            f"The input link {inp.link} has alpha{mech.ground}{inp.link} = {inp.alpha:.6g} rad/s^2 "
                            f"({sense(inp.alpha)}); its pivot is at the pole o.", f"alpha{mech.ground}{inp.link}",
                            value=(inp.alpha,), topic="input-rate",
                            params=(("link", inp.link), ("ground", mech.ground or ""), ("rate", abs(inp.alpha)),
                                    ("sense", sense(inp.alpha)))))
    elif isinstance(inp, SliderInput):
        slider = mech.slider(inp.slider)
        ctx.sliding[slider.name] = b.lay_driven_slider(slider, inp.s_ddot, slide_direction(b.pose, slider))
        ctx.coriolis[slider.name] = (0.0, 0.0)
    elif isinstance(inp, GivenInput):
        _given(ctx, inp)


def _given(ctx: _Context, given: GivenInput) -> None:
    b = ctx.b
    link = b.mechanism.link_names[0]
    for g in given.points:
        assert g.acceleration is not None
        b.add_tip(link, g.name, g.acceleration)
        b.steps.append(Step("acceleration", "known", f"a_{g.name} given", f"Lay the given a_{g.name} from the pole "
                            f"o: |a_{g.name}| = {norm(g.acceleration):.6g} {b.unit}.", g.name.lower(),
                            ((f"a_{g.name}", "magnitude and direction"),),
                            (DrawnVector(f"a_{g.name}", (0.0, 0.0), g.acceleration, "absolute"),),
                            value=g.acceleration, topic="given-point",
                            params=(("point", g.name), ("magnitude", norm(g.acceleration)))))
    first, second = given.points[0], given.points[1]
    assert first.acceleration is not None and second.acceleration is not None
    r = sub(b.world(second.name), b.world(first.name))
    w = b.omega_of(link)
    normal = scale(-w * w, r)
    rel = sub(second.acceleration, first.acceleration)
    misfit = dot(sub(rel, normal), unit(r))
    if abs(misfit) > 1e-9 * max(norm(first.acceleration), norm(second.acceleration), norm(normal), 1e-300):
        raise SceneError(f"{b.mechanism.scene.source}: given.{second.name}.acceleration: along "
                         f"{first.name}{second.name} the given accelerations differ by {dot(rel, unit(r)):.6g} "
                         f"{b.unit}, but a rigid body turning at omega = {w:.6g} rad/s needs "
                         f"{dot(normal, unit(r)):.6g} (off by {misfit:.6g})")
    mid = add(first.acceleration, normal)
    b.steps.append(Step("acceleration", "known", f"a^n_{second.name}/{first.name}",
                        f"Lay a^n_{second.name}/{first.name} = omega^2 |{first.name}{second.name}| = {norm(normal):.6g} "
                        f"{b.unit} from a, toward {first.name}; the rest, to b, is a^t_{second.name}/{first.name}.",
                        f"a^n_{second.name}/{first.name}",
                        vectors=(DrawnVector(f"a^n_{second.name}/{first.name}", first.acceleration, mid, "normal"),
                                 DrawnVector(f"a^t_{second.name}/{first.name}", mid, second.acceleration,
                                             "tangential")),
                        topic="given-normal", params=(("point", second.name), ("reference", first.name),
                                                      ("magnitude", norm(normal)))))
    read_rate(b, link, first.name, second.name, sub(second.acceleration, mid), r)


def construct_acceleration(mechanism: Mechanism, pose: Pose, plan: PositionPlan, velocity: VelocityPolygon,
                           wanted: tuple[tuple[str, str], ...] = (), unit: str = "mm", *,
                           crossing: Crossing = intersect) -> AccelerationPolygon:
    """Construct the acceleration polygon for every group of ``plan``, on top of its velocity polygon."""
    builder = PolygonBuilder(mechanism, pose, "acceleration", omega=velocity.omega, unit=unit, crossing=crossing)
    ctx = _Context(builder, velocity)
    _drive(ctx)
    where = f"at {describe_input(mechanism)}"
    for group in plan.groups:
        if isinstance(group, Dyad):
            _dyad(ctx, group, f"of group {group.name} {where}")
        else:
            from kinepoly.construct.group import acceleration_by_linear_solve

            acceleration_by_linear_solve(ctx, group)
    for link, point in wanted:
        builder.tip(link, point)
    return AccelerationPolygon(dict(builder.tips), dict(builder.rate), dict(ctx.sliding), dict(ctx.coriolis),
                               tuple(builder.steps), tuple(builder.notices),
                               {k: list(v) for k, v in builder.members.items()})
