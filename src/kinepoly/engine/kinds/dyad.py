"""Dyad kind: two unknown links joined to each other and each by one joint to a known link (RRR, RRP, RPR,
PRP, RPP), closed in closed form with its assemblies (``engine.closures``), the policy choosing which; in
the polygons the unknown tip is where two direction lines cross (``engine.lines``, ``engine.results``)."""

from __future__ import annotations

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.closures import Choice, Closure, close_dyad, other_side
from kinepoly.engine.dyad_assembly import DyadQuestion, closing_error
from kinepoly.engine.groups import Dyad, free_joints, joint_kind, slide_roles, two_slide_roles
from kinepoly.engine.kind import Kind, Later, Placed
from kinepoly.engine.lines import (
    known_pairs,
    link_length,
    parallel,
    parallel_label,
    perpendicular,
    perpendicular_label,
    read_rate,
    record_intersection,
    revolute_line,
    slide_direction,
    slide_line,
    slide_rel,
)
from kinepoly.engine.placement import Failure, Placement
from kinepoly.engine.policy import Policy
from kinepoly.engine.polygon import Line, Polygon
from kinepoly.engine.results import (
    AccelerationContext,
    VelocityContext,
    along_normal,
    along_slide,
    normals_step,
    record_crossing,
    slide_label,
)
from kinepoly.errors import MobilityError
from kinepoly.model.mechanism import Mechanism, Revolute, joint_links
from kinepoly.scene.spec import SliderSpec

__all__ = ["KIND", "acceleration", "find", "place", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> Dyad | None:
    unknown = [n for n in mechanism.link_names if n not in known]
    for i in unknown:
        for inner in free_joints(mechanism, i):
            j = [x for x in joint_links(inner) if x != i]
            if not j or j[0] in known:
                continue
            j_name = j[0]
            outer_i = [jt for jt in free_joints(mechanism, i) if any(x in known for x in joint_links(jt))]
            outer_j = [jt for jt in free_joints(mechanism, j_name) if any(x in known for x in joint_links(jt))]
            if len(outer_i) != 1 or len(outer_j) != 1:
                continue
            kind = joint_kind(outer_i[0]) + joint_kind(inner) + joint_kind(outer_j[0])
            if kind == "PPP":
                raise MobilityError(
                    f"{mechanism.scene.source}: sliders: links {i} and {j_name} are held by three sliders; "
                    "their place along the slides is not fixed (expected at least one pin in the group)"
                )
            if kind in ("PRR", "PPR"):
                return Dyad(kind[::-1], j_name, i, outer_j[0], inner, outer_i[0])
            return Dyad(kind, i, j_name, outer_i[0], inner, outer_j[0])
    return None


class _Pinned(Struct, frozen=True):
    """An RRR or RRP dyad as its polygons draw it, found once for the plan (``PlanConstants.groups``): the first
    link turns about ``p1`` on the known ``k1``, the inner pin is ``p2``; the second link turns about ``p3`` on
    ``k2`` (RRR) or slides on ``k2`` (RRP, ``p3`` None); the links' lengths and the velocity lines' labels."""

    name: str
    p1: str
    p2: str
    k1: str
    size1: float
    label1: str
    p3: str | None
    k2: str
    size2: float | None
    label2: str


def _pinned(polygon: Polygon, dyad: Dyad) -> _Pinned:
    groups = polygon.constants.groups
    key = id(dyad)
    if key in groups:
        found: _Pinned = groups[key]
        return found
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
    i, j = dyad.first, dyad.second
    p1, p2 = dyad.first_joint.point, dyad.inner.point
    k1, k2 = other_side(dyad.first_joint, i), other_side(dyad.second_joint, j)
    mech = polygon.mechanism
    if isinstance(dyad.second_joint, Revolute):
        p3: str | None = dyad.second_joint.point
        size2: float | None = link_length(mech, j, dyad.second_joint.point, p2)
        label2 = perpendicular_label(polygon, k2, dyad.second_joint.point, p2)
    else:
        p3, size2 = None, None
        label2 = parallel_label(dyad.second_joint, polygon.label(k2, p2))
    found = groups[key] = _Pinned(dyad.name, p1, p2, k1, link_length(mech, i, p1, p2),
                                  perpendicular_label(polygon, k1, p1, p2), p3, k2, size2, label2)
    return found


def velocity(state: VelocityContext, dyad: Dyad) -> None:
    polygon, sliding = state.polygon, state.sliding
    mech, i, j = polygon.mechanism, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        s = _pinned(polygon, dyad)
        p1, p2, k1, k2, p3 = s.p1, s.p2, s.k1, s.k2, s.p3
        chord = polygon.positions.chord
        line1: Line = (polygon.tip(k1, p1), chord(p1, p2)[1], s.size1)
        line2: Line
        if p3 is not None:  # RRR: perpendicular to p3 p2 through p3@k2
            line2 = (polygon.tip(k2, p3), chord(p3, p2)[1], s.size2)
        else:
            assert isinstance(dyad.second_joint, SliderSpec)
            line2 = slide_line(polygon, dyad.second_joint, k2, p2)
        label1, label2 = s.label1, s.label2
        crossing = polygon.cross_lines(line1, line2, p2, s.name, (label1, label2))
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
        if p3 is not None:
            read_rate(polygon, j, p3, p2, crossing.along_second())
        else:
            assert isinstance(dyad.second_joint, SliderSpec)
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


def acceleration(ctx: AccelerationContext, dyad: Dyad) -> None:
    b, i, j = ctx.b, dyad.first, dyad.second
    if dyad.kind in ("RRR", "RRP"):
        s = _pinned(b, dyad)
        p1, p2, k1, k2 = s.p1, s.p2, s.k1, s.k2
        line1, n1, label1 = ctx.normal_line(k1, p1, p2, i)
        vectors = [n1] if n1 else []
        if s.p3 is not None:
            p3 = s.p3
            line2, n2, label2 = ctx.normal_line(k2, p3, p2, j)
            vectors += [n2] if n2 else []
        else:
            assert isinstance(dyad.second_joint, SliderSpec)
            line2, laid = ctx.slide_line(dyad.second_joint, k2, j, p2)
            label2 = slide_label(dyad.second_joint)
            vectors += laid
        if b.record:
            normals_step(ctx, vectors)
        crossing = b.cross_lines(line1, line2, p2, s.name, (label1, label2))
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
            record_crossing(ctx, p2, equation, line1, line2, (label1, label2), crossing, vectors,
                            (direction1, direction2))
        read_rate(b, i, p1, p2, crossing.along_first)
        if s.p3 is not None:
            read_rate(b, j, s.p3, p2, crossing.along_second())
        else:
            assert isinstance(dyad.second_joint, SliderSpec)
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
            record_crossing(ctx, at, f"a_{at} = a_{q} + a^n_{at}/{q} + a^t_{at}/{q} = a_{p}{cor} + a_{at}/{p}",
                    line1, line2,
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


def place(mechanism: Mechanism, group: Dyad, placed: Placement, policy: Policy, later: Later) -> Placed:
    """Close the dyad at every row; rows where it does not close are the policy's to raise or to mark, and
    where its assemblies are told apart the policy chooses one (or, having carried both through the groups
    after it with ``later``, the whole placement)."""
    closure = close_dyad(mechanism, placed.poses, group, placed.values)
    if closure.near is not None:
        placed = replace(placed, near=(*placed.near, Failure(group.name, closure.joint, closure.near[0],
                                                             closure.near[1])))
    if not np.logical_and.reduce(closure.ok):  # closure.ok.all() without its Python wrapper
        bad = placed.ok & ~closure.ok
        policy.cannot_close(lambda: closing_error(mechanism, closure))
        placed = replace(placed, ok=placed.ok & closure.ok,
                         failures=(*placed.failures, Failure(group.name, closure.joint, bad, closure.why)))
    choice: Choice = 0
    if len(closure.telling) == 2:
        base = placed

        def carried_through(label: int, base: Placement = base, closure: Closure = closure) -> Placement:
            return later(base.with_poses({**base.poses, **closure.place(label)}))

        chosen = policy.assemble(mechanism, DyadQuestion(closure, carried_through), placed)
        if isinstance(chosen, Placement):
            return chosen, True
        choice = chosen
    return placed.with_poses({**placed.poses, **closure.place(choice)}), False


KIND: Kind[Dyad] = Kind(find, place, velocity, acceleration, batched=True)
