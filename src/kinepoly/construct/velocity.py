"""The velocity polygon, constructed dyad by dyad by intersecting two direction lines.

For each dyad the unknown tip is where two lines cross: perpendicular to the link for a
turning relative velocity (v_B/A is perpendicular to AB), parallel to the slide for a sliding
one. Omega of a link is then read off the polygon: |v_B/A| / |AB|, its sense from the
direction of v_B/A.
"""

from __future__ import annotations

from dataclasses import dataclass

from kinepoly.construct.builder import Crossing, PolygonBuilder, sense
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.errors import SceneError
from kinepoly.geom import Line, intersect
from kinepoly.geom.vec import Vec, cross, dot, norm, perp, rotate, sub, unit
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.notice import Notice
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput, SliderSpec
from kinepoly.engine.plan import Dyad, PositionPlan, slide_roles, two_slide_roles
from kinepoly.model.pose import Pose
from kinepoly.solve.position import describe_input

__all__ = ["VelocityPolygon", "construct_velocity", "read_rate", "slide_direction"]


@dataclass(frozen=True)
class VelocityPolygon:
    """Tips (physical velocities, pole at 0), omegas, sliding velocities, steps."""

    tips: dict[str, Vec]
    omega: dict[str, float]
    sliding: dict[str, Vec]
    steps: tuple[Step, ...]
    notices: tuple[Notice, ...]
    members: dict[str, list[tuple[str, Vec]]]


def slide_direction(pose: Pose, slider: SliderSpec) -> Vec:
    return rotate((1.0, 0.0), pose.links[slider.guide].theta + slider.angle_rad)


def read_rate(builder: PolygonBuilder, link: str, first: str, second: str, relative: Vec, at: Vec) -> float:
    """Read omega (or alpha, from a tangential term) of ``link`` off the polygon, with a step."""
    length = norm(at)
    value = (1.0 if cross(at, relative) >= 0 else -1.0) * norm(relative) / length
    symbol = "omega" if builder.kind == "velocity" else "alpha"
    term = f"v_{second}/{first}" if builder.kind == "velocity" else f"a^t_{second}/{first}"
    ground = builder.mechanism.ground or ""
    text = (f"{symbol}{ground}{link} = |{term}| / |{first}{second}| = {norm(relative):.6g} / {length:.6g} = "
            f"{abs(value):.6g} {'rad/s' if symbol == 'omega' else 'rad/s^2'}, {sense(value)} "
            f"(the sense in which {term} turns {second} about {first}).")
    builder.steps.append(Step(builder.kind, "read", f"{symbol}{ground}{link} = |{term}| / |{first}{second}|",
                              text, f"{symbol}{ground}{link}", value=(value,), topic="read",
                              params=(("link", link), ("ground", ground), ("term", term), ("first", first),
                                      ("second", second), ("magnitude", norm(relative)), ("length", length),
                                      ("rate", abs(value)), ("sense", sense(value)))))
    builder.set_rate(link, value)
    return value


def _where(mechanism: Mechanism, dyad: Dyad) -> str:
    return f"of group {dyad.name} at {describe_input(mechanism)}"


def _drive(builder: PolygonBuilder, sliding: dict[str, Vec]) -> None:
    mech, pose = builder.mechanism, builder.pose
    inp = mech.scene.input
    if isinstance(inp, LinkInput):
        builder.set_rate(inp.link, inp.omega)
        builder.steps.append(Step("velocity", "known", f"omega{mech.ground}{inp.link} given",
                                  f"The input link {inp.link} turns at omega{mech.ground}{inp.link} = "
                                  f"{inp.omega:.6g} rad/s ({sense(inp.omega)}); its pivot is at the pole o.",
                                  f"omega{mech.ground}{inp.link}", value=(inp.omega,), topic="input-rate",
                                  params=(("link", inp.link), ("ground", mech.ground or ""),
                                          ("rate", abs(inp.omega)), ("sense", sense(inp.omega)))))
    elif isinstance(inp, SliderInput):
        slider = mech.slider(inp.slider)
        sliding[slider.name] = builder.lay_driven_slider(slider, inp.s_dot, slide_direction(pose, slider))
    elif isinstance(inp, GivenInput):
        _given(builder, inp)


def _given(builder: PolygonBuilder, given: GivenInput) -> None:
    link = builder.mechanism.link_names[0]
    for g in given.points:
        builder.add_tip(link, g.name, g.velocity)
        builder.steps.append(Step("velocity", "known", f"v_{g.name} given", f"Lay the given v_{g.name} from the "
                                  f"pole o: |v_{g.name}| = {norm(g.velocity):.6g} {builder.unit}.", g.name.lower(),
                                  ((f"v_{g.name}", "magnitude and direction"),),
                                  (DrawnVector(f"v_{g.name}", (0.0, 0.0), g.velocity, "absolute"),),
                                  value=g.velocity, topic="given-point",
                                  params=(("point", g.name), ("magnitude", norm(g.velocity)))))
    first, second = given.points[0], given.points[1]
    at = sub(builder.world(second.name), builder.world(first.name))
    rel = sub(second.velocity, first.velocity)
    along = dot(rel, unit(at))
    if abs(along) > 1e-9 * max(norm(first.velocity), norm(second.velocity), 1e-300):
        raise SceneError(f"{builder.mechanism.scene.source}: given.{second.name}.velocity: the given velocities of "
                         f"{first.name} and {second.name} differ by {along:.6g} {builder.unit} along "
                         f"{first.name}{second.name}; a rigid body allows none (make v_{second.name}/{first.name} "
                         f"perpendicular to {first.name}{second.name})")
    read_rate(builder, link, first.name, second.name, rel, at)


def _revolute_line(builder: PolygonBuilder, known_link: str, known_point: str, point: str) -> Line:
    """Locus of v_point: through the tip of known_point, perpendicular to known_point -> point."""
    start = builder.tip(known_link, known_point)
    r = sub(builder.world(point), builder.world(known_point))
    return Line(start, perp(r), f"perpendicular to {known_point}{point} through {builder.label(known_link, known_point).lower()}")


def _perpendicular(builder: PolygonBuilder, term: str, known_link: str, known_point: str, point: str) -> Direction:
    """What ``_revolute_line`` draws, as data."""
    return Direction(term, "perpendicular", f"{known_point}{point}", builder.label(known_link, known_point).lower())


def _parallel(builder: PolygonBuilder, term: str, slider: SliderSpec, other: str, point: str) -> Direction:
    """What ``_slide_line`` draws (and the RPR dyad's slide line), as data."""
    return Direction(term, "parallel", slider.name, builder.label(other, point).lower())


def _slide_line(builder: PolygonBuilder, slider: SliderSpec, other: str, point: str) -> Line:
    """Locus of v_point (a point of the side opposite ``other``): through the tip of point@other."""
    start = builder.tip(other, point)
    e = slide_direction(builder.pose, slider)
    return Line(start, e, f"parallel to slider {slider.name} through {builder.label(other, point).lower()}")


def _other(joint: Revolute | SliderSpec, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _record_intersection(builder: PolygonBuilder, dyad: Dyad, label: str, equation: str,
                         first: Line, second: Line, value: Vec, known: tuple[tuple[str, str], ...],
                         directions: tuple[Direction, Direction]) -> None:
    text = (f"Through the known tips draw the two directions: {first.label}, and {second.label}. "
            f"They cross at {label.lower()}: o{label.lower()} is v_{label} = ({value[0]:.6g}, {value[1]:.6g}) "
            f"{builder.unit}.")
    builder.steps.append(Step("velocity", "intersection", equation, text, label.lower(), known,
                              lines=(first, second), value=value, topic="intersection", params=(("point", label),),
                              directions=directions))


def _slide_rel(builder: PolygonBuilder, slider: SliderSpec, link: str, point: str, sliding: dict[str, Vec]) -> None:
    """Velocity of the block relative to the guide, from the tips of ``point`` on both sides."""
    other = slider.guide if link == slider.block else slider.block
    on_link = builder.tips[builder.label(link, point)]
    on_other = builder.tip(other, point)
    rel = sub(on_link, on_other) if link == slider.block else sub(on_other, on_link)
    sliding[slider.name] = rel


def _dyad(builder: PolygonBuilder, dyad: Dyad, sliding: dict[str, Vec]) -> None:
    mech, i, j = builder.mechanism, dyad.first, dyad.second
    where = _where(mech, dyad)
    if dyad.kind in ("RRR", "RRP"):
        assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
        p1, p2 = dyad.first_joint.point, dyad.inner.point
        line1 = _revolute_line(builder, _other(dyad.first_joint, i), p1, p2)
        direction1 = _perpendicular(builder, f"v_{p2}/{p1}", _other(dyad.first_joint, i), p1, p2)
        if isinstance(dyad.second_joint, Revolute):
            p3 = dyad.second_joint.point
            line2 = _revolute_line(builder, _other(dyad.second_joint, j), p3, p2)
            direction2 = _perpendicular(builder, f"v_{p2}/{p3}", _other(dyad.second_joint, j), p3, p2)
            equation = f"v_{p2} = v_{p1} + v_{p2}/{p1} = v_{p3} + v_{p2}/{p3}"
            known = ((f"v_{p1}", "magnitude and direction"), (f"v_{p2}/{p1}", "direction"),
                     (f"v_{p3}", "magnitude and direction"), (f"v_{p2}/{p3}", "direction"))
        else:
            k2 = _other(dyad.second_joint, j)
            line2 = _slide_line(builder, dyad.second_joint, k2, p2)
            at2 = builder.label(k2, p2)
            direction2 = _parallel(builder, f"v_{p2}/{at2}", dyad.second_joint, k2, p2)
            equation = f"v_{p2} = v_{p1} + v_{p2}/{p1} = v_{at2} + v_{p2}/{at2}"
            known = ((f"v_{p1}", "magnitude and direction"), (f"v_{p2}/{p1}", "direction"),
                     (f"v_{at2}", "magnitude and direction"), (f"v_{p2}/{at2}", "direction"))
        value = builder.cross_lines(line1, line2, p2, where)
        builder.add_tip(i, p2, value)
        _record_intersection(builder, dyad, p2, equation, line1, line2, value, known, (direction1, direction2))
        read_rate(builder, i, p1, p2, sub(value, line1.through), sub(builder.world(p2), builder.world(p1)))
        if isinstance(dyad.second_joint, Revolute):
            p3 = dyad.second_joint.point
            read_rate(builder, j, p3, p2, sub(value, line2.through), sub(builder.world(p2), builder.world(p3)))
        else:
            _slide_rel(builder, dyad.second_joint, j, p2, sliding)
    elif dyad.kind == "RPR":
        r = slide_roles(dyad)
        q, p = r.guide_pin, r.block_pin
        line1 = _revolute_line(builder, r.guide_known, q, p)
        start = builder.tip(r.block_known, p)
        line2 = Line(start, slide_direction(builder.pose, r.slider),
                     f"parallel to slider {r.slider.name} through {p.lower()}")
        at = builder.label(r.guide, p)
        value = builder.cross_lines(line1, line2, at, where)
        builder.add_tip(r.guide, p, value)
        _record_intersection(builder, dyad, at, f"v_{at} = v_{q} + v_{at}/{q} = v_{p} + v_{at}/{p}", line1, line2,
                             value, ((f"v_{q}", "magnitude and direction"), (f"v_{at}/{q}", "direction"),
                                     (f"v_{p}", "magnitude and direction"), (f"v_{at}/{p}", "direction")),
                             (_perpendicular(builder, f"v_{at}/{q}", r.guide_known, q, p),
                              _parallel(builder, f"v_{at}/{p}", r.slider, r.block_known, p)))
        read_rate(builder, r.guide, q, at, sub(value, line1.through), sub(builder.world(p), builder.world(q)))
        sliding[r.slider.name] = sub(start, value)
    else:  # PRP and RPP: both links' omegas are known from their guides, two slide lines cross
        t = two_slide_roles(dyad, mech)
        if t.pin is not None and t.pin_known is not None:
            builder.tip(t.pin_known, t.pin)
        point = t.point
        line1 = _slide_line(builder, t.first_slider, t.side1, point)
        line2 = _slide_line(builder, t.second_slider, t.side2, point)
        value = builder.cross_lines(line1, line2, point, where)
        builder.add_tip(t.moving, point, value)
        a1, a2 = builder.label(t.side1, point), builder.label(t.side2, point)
        _record_intersection(builder, dyad, point, f"v_{point} = v_{a1} + v_{point}/{a1} = v_{a2} + v_{point}/{a2}",
                             line1, line2, value, ((f"v_{a1}", "magnitude and direction"),
                                                   (f"v_{point}/{a1}", "direction"),
                                                   (f"v_{a2}", "magnitude and direction"),
                                                   (f"v_{point}/{a2}", "direction")),
                             (_parallel(builder, f"v_{point}/{a1}", t.first_slider, t.side1, point),
                              _parallel(builder, f"v_{point}/{a2}", t.second_slider, t.side2, point)))
        _slide_rel(builder, t.first_slider, t.first_relative, point, sliding)
        _slide_rel(builder, t.second_slider, j, point, sliding)


def construct_velocity(mechanism: Mechanism, pose: Pose, plan: PositionPlan,
                       wanted: tuple[tuple[str, str], ...] = (), unit: str = "mm", *,
                       crossing: Crossing = intersect) -> VelocityPolygon:
    """Construct the velocity polygon for every group of ``plan``, then the tips of ``wanted``.

    ``wanted`` holds (link, point) pairs: the velocity of ``point`` as a point of ``link``;
    ``crossing`` crosses two direction lines (the bench compares other primitives).
    """
    builder = PolygonBuilder(mechanism, pose, "velocity", unit=unit, crossing=crossing)
    sliding: dict[str, Vec] = {}
    _drive(builder, sliding)
    for group in plan.groups:
        if isinstance(group, Dyad):
            _dyad(builder, group, sliding)
        else:
            from kinepoly.construct.group import velocity_by_linear_solve

            velocity_by_linear_solve(builder, group, sliding)
    for link, point in wanted:
        builder.tip(link, point)
    return VelocityPolygon(dict(builder.tips), dict(builder.rate), dict(sliding), tuple(builder.steps),
                           tuple(builder.notices), {k: list(v) for k, v in builder.members.items()})
