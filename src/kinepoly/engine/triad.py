"""A class-3 group (a triad) constructed through its Assur point, velocity and acceleration, over rows.

The group is a ternary link T held by three legs, each joining T to a known link. Every leg
says, for one point Q of T (or under T), that the tip of Q as a point of T is a known tip plus
an unknown multiple of a known direction e:

- a binary link L pinned to T at X and to a known link at K: Q = X, from the tip of K,
  e perpendicular to KX (the unknown multiple is omega_L, or alpha_L);
- a block pinned to T at X, sliding on a known guide: Q = X, from the tip of X on the guide,
  e along the slide;
- a block pinned to a known link at K, sliding in a slot of T: Q = K (a point under T), from
  the tip of K, e along the slot;
- two links held by a driven joint (a cylinder: the barrel pinned to a known link at K, the rod to T
  at X, or the other way round): once the stroke is given, a binary link K X whose length changes at a
  known rate: Q = X, from the tip of K plus the drive's relative term, e perpendicular to KX
  (``engine.driven_leg``).

The line of a leg is the line through Q perpendicular to e (a binary link's own line). Where
the lines of two legs cross is the Assur point S, a point of T. Since S - Q is perpendicular to
e, the term omega_T x QS of T is along e too: the tip of S lies on the line through each of the
two legs' known tips along its e, and their crossing is s. The third leg's point then lies on
the line through s perpendicular to SQ and on its own leg's line; the other two legs' points
on the line through that tip perpendicular to the segment between them and on their own lines.
For accelerations the same lines are drawn after the known terms: the legs' normal or Coriolis
terms, and T's normal terms toward S (the tangential terms of the leg and of T at S are both
along e, so they share one line). The pair of legs whose lines cross at the larger angle is
taken for S: the pair whose construction crosses all its lines at the steepest angles (the
largest smallest sine), so that where the Assur point runs off to infinity (the lines parallel)
another pair is taken; the step says which legs give S.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from msgspec import Struct

from kinepoly.engine import driven_leg
from kinepoly.engine.cam_contact import centre_label, face_direction
from kinepoly.engine.driven_leg import Leg
from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.lines import read_rate, slide_direction
from kinepoly.engine.polygon import LineCrossing, Polygon
from kinepoly.engine.results import AccelerationContext
from kinepoly.engine.steps import Direction, DrawnVector, Step
from kinepoly.errors import SingularityError
from kinepoly.geom.arrays import Points, Reals, cross_lines
from kinepoly.geom.tolerances import PARALLEL_SIN
from kinepoly.model.mechanism import Mechanism, Revolute, joint_links
from kinepoly.scene.spec import SliderSpec

__all__ = ["Leg", "Triad", "acceleration_by_assur_point", "triad_of", "velocity_by_assur_point"]


class Triad(Struct, frozen=True):
    """A class-3 group: ``ternary`` held by three legs; ``assur`` names its Assur point."""

    ternary: str
    legs: tuple[Leg, Leg, Leg]
    assur: str


def _leg(mechanism: Mechanism, ternary: str, link: str, inner: Revolute | SliderSpec,
         outer: Revolute | SliderSpec) -> Leg | None:
    known = next(x for x in joint_links(outer) if x != link)
    if isinstance(inner, Revolute) and isinstance(outer, Revolute):
        return Leg("pin", link, inner.point, known, outer.point, None)
    if isinstance(inner, Revolute) and isinstance(outer, SliderSpec) and outer.block == link:
        return Leg("slide", link, inner.point, known, None, outer) if outer.point == inner.point else None
    if isinstance(inner, SliderSpec) and isinstance(outer, Revolute) and inner.guide == ternary \
            and inner.block == link and inner.point == outer.point:
        return Leg("slot", link, outer.point, known, outer.point, inner)
    return None


def triad_of(mechanism: Mechanism, group: NewtonGroup) -> Triad | None:
    """The triad a group is, or None (a group of another shape keeps its linear solve). A floating follower
    on a spline cam with two legs of its own is a triad whose third leg is the pair's equivalent link K W."""
    if group.cams:
        return _floating_triad(mechanism, group)
    inside = [d for d in group.drives if d.moving in group.links and d.base in group.links]
    if len(group.links) != 4 + len(inside) or len(group.joints) != 6 + len(inside):
        return None
    for ternary in group.links:
        legs = _legs(mechanism, group, ternary, 3)
        if legs is None:
            continue
        return Triad(ternary, (legs[0], legs[1], legs[2]), _assur_name(mechanism, ternary)) if legs else None
    return None


def _assur_name(mechanism: Mechanism, ternary: str) -> str:
    return next(n for n in ("S", f"S{ternary}", f"S_{ternary}", "S*") if not mechanism.links_of_point(n))


def _legs(mechanism: Mechanism, group: NewtonGroup, ternary: str, count: int) -> list[Leg] | None:
    """The legs of ``ternary`` in the group (``count`` of them); None where it does not have that many, an
    empty list where one of them is no leg."""
    inside = set(group.links)
    inner = [j for j in group.joints if ternary in joint_links(j) and set(joint_links(j)) <= inside]
    legs_links = [next(x for x in joint_links(j) if x != ternary) for j in inner]
    if len(inner) != count or len(set(legs_links)) != count:
        return None
    legs = []
    for link, joint in zip(legs_links, inner, strict=True):
        outer = [j for j in group.joints if link in joint_links(j) and not set(joint_links(j)) <= inside]
        leg = (_leg(mechanism, ternary, link, joint, outer[0]) if len(outer) == 1
               else _driven_leg(group, ternary, link, joint) if not outer else None)
        if leg is None:
            return []
        legs.append(leg)
    return legs


def _driven_leg(group: NewtonGroup, ternary: str, link: str, inner: Revolute | SliderSpec) -> Leg | None:
    """``link`` pinned to the ternary and held by a driven joint to a ``carrier`` of the group that is pinned
    to a known link, and to nothing else: one leg once the input is given (``engine.driven_leg``)."""
    if not isinstance(inner, Revolute):
        return None
    inside = set(group.links)
    for drive in group.drives:
        if link not in (drive.moving, drive.base) or ternary in (drive.moving, drive.base):
            continue
        carrier = drive.base if link == drive.moving else drive.moving
        own = [j for j in group.joints if link in joint_links(j)]
        theirs = [j for j in group.joints if carrier in joint_links(j) and j != drive.joint]
        if carrier not in inside or len(own) != 2 or len(theirs) != 1 or not isinstance(theirs[0], Revolute):
            continue
        known = next(x for x in joint_links(theirs[0]) if x != carrier)
        if known in inside:
            continue
        return Leg("pin", link, inner.point, known, theirs[0].point, None, carrier=carrier, drive=drive)
    return None


def _floating_triad(mechanism: Mechanism, group: NewtonGroup) -> Triad | None:
    """The follower of the group's one spline cam as the ternary: its two legs, and the pair's equivalent
    link K W (pinned to the cam at K, to the follower at W) as the third."""
    if len(group.cams) != 1 or len(group.links) != 3 or len(group.joints) != 4:
        return None
    cam = group.cams[0]
    legs = _legs(mechanism, group, cam.follower, 2)
    if not legs:
        return None
    k = centre_label(cam)
    if cam.kind == "flat":
        legs.append(Leg("face", k, k, cam.cam, None, None, cam.name))
    else:
        legs.append(Leg("pin", f"{k}{cam.point}", cam.point or "", cam.cam, k, None, cam.name))
    return Triad(cam.follower, (legs[0], legs[1], legs[2]), _assur_name(mechanism, cam.follower))


# -- the construction, shared by both polygons ----------------------------------------------------


class _LegLine(Struct, frozen=True):
    """A leg's own line in the polygon (through the known tip, after its known terms, along e), and
    where Q is on the mechanism."""

    at: Points
    through: Points
    direction: Points
    vectors: tuple[DrawnVector, ...]


class _Built(Struct, frozen=True):
    """One choice of the third leg m, at every row: the tip of S, of each Q (as a point of T), how far
    along each leg's own line (the leg's rate or slide), T's rate, and the sines of the crossings."""

    s: Points
    tips: tuple[Points, Points, Points]
    along: tuple[Reals, Reals, Reals]
    rate: Reals
    sines: tuple[Reals, Reals, Reals, Reals]


_ORDERS = ((1, 2, 0), (0, 2, 1), (0, 1, 2))
"""(first, second, third): S from the lines of the first two legs, the third leg from S."""


def _build(legs: list[_LegLine], s_world: Points, normal_t: Callable[[Points], Points], order: tuple[int, int, int],
           ) -> _Built:
    """The construction with S from legs order[0], order[1] and m = order[2]; ``normal_t(r)`` is T's
    known term for the segment r (0 for velocities, -omega_T^2 r for accelerations)."""
    a, b, m = order
    la, lb, lm = legs[a], legs[b], legs[m]
    # S: each of the two legs' lines after T's normal term from Q to S
    first = cross_lines(la.through + normal_t(s_world - la.at), la.direction,
                        lb.through + normal_t(s_world - lb.at), lb.direction)
    s = first.point
    r_m = lm.at - s_world
    third = cross_lines(s + normal_t(r_m), 1j * r_m, lm.through, lm.direction)
    rate = third.along_first
    tip_m = third.point
    tips: list[Points] = [tip_m, tip_m, tip_m]
    along: list[Reals] = [rate, rate, rate]
    sines = [first.sin_angle, third.sin_angle]
    along[m] = third.along_second()
    for k in (a, b):
        r = legs[k].at - lm.at
        crossing = cross_lines(tip_m + normal_t(r), 1j * r, legs[k].through, legs[k].direction)
        tips[k] = crossing.point
        along[k] = crossing.along_second()
        sines.append(crossing.sin_angle)
    return _Built(s, (tips[0], tips[1], tips[2]), (along[0], along[1], along[2]), rate,
                  (sines[0], sines[1], sines[2], sines[3]))


def _assur_world(legs: list[_LegLine], order: tuple[int, int, int]) -> tuple[Points, Reals]:
    """Where the lines of legs order[0] and order[1] cross on the mechanism, and the sine of their angle."""
    la, lb = legs[order[0]], legs[order[1]]
    crossing = cross_lines(la.at, 1j * la.direction, lb.at, 1j * lb.direction)
    return crossing.point, crossing.sin_angle


def _construct(polygon: Polygon, triad: Triad, legs: list[_LegLine],
               normal_t: Callable[[Points], Points]) -> tuple[_Built, Points, tuple[int, int, int]]:
    """Every choice of the pair of legs, the best one taken at every row; also row 0's choice."""
    orders = _ORDERS
    assur = [_assur_world(legs, order) for order in orders]
    built = [_build(legs, assur[k][0], normal_t, orders[k]) for k in range(3)]
    quality = np.stack([np.min(np.abs(np.stack([assur[k][1], *built[k].sines])), axis=0) for k in range(3)])
    best = np.argmax(np.where(np.isfinite(quality), quality, -1.0), axis=0)

    def pick(values: list[Points] | list[Reals]) -> Points:
        out = values[0]
        for k in (1, 2):
            out = np.where(best == k, values[k], out)
        return np.asarray(out)

    chosen = _Built(pick([b.s for b in built]), tuple(pick([b.tips[q] for b in built]) for q in range(3)),  # type: ignore[arg-type]
                    tuple(pick([b.along[q] for b in built]).real for q in range(3)),  # type: ignore[arg-type]
                    pick([b.rate for b in built]).real,
                    tuple(pick([b.sines[q] for b in built]).real for q in range(4)))  # type: ignore[arg-type]
    s_world = pick([a for a, _ in assur])
    s_sin = pick([sin for _, sin in assur]).real
    tips = ", ".join(leg.point for leg in triad.legs)  # which leg's crossing each sine is varies with the pair
    for what, sin in zip((triad.assur, tips, tips, tips), chosen.sines, strict=True):
        polygon.crossings.append(LineCrossing(polygon.kind, _name(triad), what, np.minimum(np.abs(sin), np.abs(s_sin)),
                                              chosen.rate))
    if polygon.strict:
        worst = min(abs(float(sin[0])) for sin in (s_sin, *chosen.sines))
        if not worst > PARALLEL_SIN:
            raise SingularityError(
                f"singular position of the triad {_name(triad)}: its {polygon.kind} direction lines are parallel "
                "for every pair of legs (the Assur point is at infinity for each pair, or the third leg is in "
                f"line with it); the {polygon.kind}s of the group are not determined by the input")
    return chosen, s_world, orders[int(best[0])]


def _face_direction(polygon: Polygon, leg: Leg) -> Points:
    """The unit direction of the ternary's flat face at every row (a face leg's own line runs along it)."""
    return face_direction(polygon.positions.poses, next(c for c in polygon.mechanism.scene.cams
                                                        if c.name == leg.equivalent))


def _name(triad: Triad) -> str:
    return f"{triad.ternary}-" + "-".join(leg.name for leg in triad.legs) + " (triad)"


# -- velocity ---------------------------------------------------------------------------------------


def _velocity_leg(polygon: Polygon, triad: Triad, leg: Leg) -> _LegLine:
    at = polygon.world(leg.point)
    if leg.drive is not None:
        return _LegLine(at, *driven_leg.velocity_terms(polygon, leg))
    if leg.kind == "pin":
        assert leg.pin is not None
        start = polygon.tip(leg.known, leg.pin)
        direction = np.asarray(1j * (at - polygon.world(leg.pin)))
    elif leg.kind == "face":
        start = polygon.tip(leg.known, leg.point)
        direction = _face_direction(polygon, leg)
    else:
        assert leg.slider is not None
        start = polygon.tip(leg.known, leg.point)
        direction = slide_direction(polygon.positions, leg.slider)
    return _LegLine(at, start, direction, ())


def velocity_by_assur_point(polygon: Polygon, triad: Triad, sliding: dict[str, Points],
                            equivalent: dict[str, Points] | None = None) -> None:
    """The triad's velocity polygon through its Assur point (``equivalent``: where an equivalent link's
    omega is kept, by its pair)."""
    legs = [_velocity_leg(polygon, triad, leg) for leg in triad.legs]
    built, s_world, order = _construct(polygon, triad, legs, lambda r: polygon.zero)
    _finish(polygon, triad, legs, built, s_world, order)
    for leg, along, tip in zip(triad.legs, built.along, built.tips, strict=True):
        if leg.equivalent and equivalent is not None:  # K W's omega; a face's block: its velocity over the face
            equivalent[leg.equivalent] = np.asarray(polygon.tip(leg.known, leg.point) - tip if leg.kind == "face"
                                                    else along + 0j)
    for leg, tip in zip(triad.legs, built.tips, strict=True):
        if leg.slider is not None:
            on_leg, on_t = (polygon.tip(leg.link, leg.point), tip) if leg.kind == "slot" else (
                tip, polygon.tip(leg.known, leg.point))
            sliding[leg.slider.name] = np.asarray(on_leg - on_t)
    for leg, along, tip in zip(triad.legs, built.along, built.tips, strict=True):
        if leg.drive is not None:
            driven_leg.finish_velocity(polygon, leg, tip, along, sliding)


def _finish(polygon: Polygon, triad: Triad, legs: list[_LegLine], built: _Built, s_world: Points,
            order: tuple[int, int, int], normal_t: Callable[[Points], Points] | None = None) -> None:
    """Register the tips and rates the construction found, and record its steps (row 0); ``normal_t`` is
    T's normal term for a segment (accelerations; None for velocities)."""
    t = triad.ternary
    polygon.positions.add_point(triad.assur, s_world)
    polygon.add_virtual_tip(t, triad.assur, built.s)
    labels = []
    for leg, tip in zip(triad.legs, built.tips, strict=True):
        labels.append(polygon.add_tip(t, leg.point, tip))
    if polygon.record:
        _record(polygon, triad, legs, built, order, labels, s_world, normal_t)
    read_rate(polygon, t, triad.assur, labels[order[2]], built.rate)
    for leg, along in zip(triad.legs, built.along, strict=True):
        if leg.kind == "pin" and not leg.equivalent and leg.drive is None:
            assert leg.pin is not None
            read_rate(polygon, leg.link, leg.pin, leg.point, along)


def _record(polygon: Polygon, triad: Triad, legs: list[_LegLine], built: _Built, order: tuple[int, int, int],
            labels: list[str], s_world: Points, normal_t: Callable[[Points], Points] | None) -> None:
    """The steps: the Assur point on the mechanism, its tip, then the third leg's point and the other two.
    For accelerations each tangential term's line starts at the end of the normal terms laid before it (the
    legs' own, and T's toward S, or toward the point found before), and a step lays those normal terms."""
    a, b, m = order
    s = triad.assur
    sym = polygon.symbol
    t = triad.ternary
    accelerating = polygon.kind == "acceleration" and normal_t is not None
    laid: set[str] = set()  # the normal terms laid in this group so far

    def leg_direction(k: int, term: str, after: str) -> Direction:
        leg = triad.legs[k]
        through = polygon.label(leg.known, leg.pin if leg.kind == "pin" and leg.pin else leg.point).lower()
        if leg.kind == "pin":
            return Direction(term, "perpendicular", f"{leg.pin}{leg.point}", through, after=after)
        if leg.kind == "face":
            return Direction(term, "face", t, through, after=after)
        assert leg.slider is not None
        return Direction(term, "parallel", leg.slider.name, through, after=after)

    def line_label(k: int, term: str) -> str:
        """What the line carries and how it runs (as a dyad's lines say it: the renderer tells terms by it)."""
        leg = triad.legs[k]
        if leg.kind == "pin":
            return f"{term} perpendicular to {leg.pin}{leg.point}"
        if leg.kind == "face":
            return f"{term} parallel to the flat face of {t}"
        assert leg.slider is not None
        return f"{term} parallel to slider {leg.slider.name}"

    def leg_term(k: int) -> str:
        leg = triad.legs[k]
        if leg.kind == "pin":
            point = polygon.label(leg.carrier, leg.point) if leg.drive is not None else leg.point
            return f"{sym}{'^t' if polygon.kind == 'acceleration' else ''}_{point}/{leg.pin}"
        return f"{sym}_{labels[k]}/{polygon.label(leg.known, leg.point)}"

    def leg_known(k: int) -> str:
        leg = triad.legs[k]
        return f"{sym}_{polygon.label(leg.known, leg.pin if leg.kind == 'pin' and leg.pin else leg.point)}"

    def ternary_normal(point: str, reference: str, start: Points, r: Points) -> tuple[Points, DrawnVector | None]:
        """T's normal term of ``point`` about ``reference`` (r from reference to point) laid from ``start``."""
        if not accelerating:
            return start, None
        assert normal_t is not None
        end = np.asarray(start + normal_t(r))
        return end, DrawnVector(f"a^n_{point}/{reference}", polygon.vec(start), polygon.vec(end), "normal")

    def lay_normals(vectors: tuple[DrawnVector, ...]) -> None:
        """The step that lays the normal terms not laid before (a dyad's normals step)."""
        fresh = tuple(v for v in vectors if v.term == "normal" and v.label not in laid and not _equivalent_normal(v))
        laid.update(v.label for v in vectors if v.term == "normal")
        if accelerating and fresh:
            polygon.step(Step(polygon="acceleration", kind="known", equation=" and ".join(v.label for v in fresh),
                              result=", ".join(v.label for v in fresh),
                              known=tuple((v.label, "magnitude and direction") for v in fresh), vectors=fresh,
                              topic="normals"))

    def _equivalent_normal(vector: DrawnVector) -> bool:
        """A normal term of a spline cam pair's equivalent link (its omega is the pair's, not a link's)."""
        return any(leg.equivalent and vector in legs[k].vectors for k, leg in enumerate(triad.legs))

    la, lb = triad.legs[a], triad.legs[b]
    polygon.step(Step(polygon=polygon.kind, kind="known", equation=f"{s} = line of leg {la.name} x line of "
                      f"leg {lb.name}", result=s, topic="assur-point",
                      params=(("point", s), ("ternary", t), ("first", la.name), ("second", lb.name),
                              *_leg_line("first", la, t), *_leg_line("second", lb, t), ("third", triad.legs[m].name))))
    # the tip of S: from each leg's known tip its known terms and T's normal term toward S, then the line along
    # the leg's direction, which carries the leg's term and T's tangential term about S (parallel)
    vectors: tuple[DrawnVector, ...] = ()
    lines = []
    directions = []
    sides = []
    for k in (a, b):
        end, normal = ternary_normal(s, labels[k], legs[k].through, np.asarray(s_world - legs[k].at))
        own = legs[k].vectors + ((normal,) if normal is not None else ())
        vectors += own
        term = f"{leg_term(k)} + {sym}{'^t' if accelerating else ''}_{s}/{labels[k]}"
        after = own[-1].label if own else ""
        lines.append(polygon.step_line((end, legs[k].direction, None), line_label(k, term)))
        directions.append(leg_direction(k, term, after))
        sides.append(" + ".join([leg_known(k), *(v.label for v in own), term]))
    lay_normals(vectors)
    polygon.step(Step(
        polygon=polygon.kind, kind="intersection", equation=f"{sym}_{s} = {sides[0]} = {sides[1]}",
        result=s.lower(),
        known=tuple((v.label, "magnitude and direction") for v in vectors) + tuple((d.term, "direction")
                                                                                  for d in directions),
        vectors=vectors, lines=(lines[0], lines[1]), value=polygon.vec(built.s), topic="assur-tip",
        params=(("point", s), ("ternary", t), ("first", la.name), ("second", lb.name)),
        directions=(directions[0], directions[1])))
    # the third leg's point from S, then the other two from it: T's normal term, then its tangential line
    for k, from_k in ((m, -1), (a, m), (b, m)):
        ref = s if from_k < 0 else labels[from_k]
        ref_point = s if from_k < 0 else triad.legs[from_k].point
        point = triad.legs[k].point
        start = built.s if from_k < 0 else built.tips[from_k]
        r = np.asarray(polygon.world(point) - polygon.world(ref_point))
        end, normal = ternary_normal(labels[k], ref, start, r)
        first_term = f"{sym}{'^t' if accelerating else ''}_{labels[k]}/{ref}"
        own = ((normal,) if normal is not None else ()) + legs[k].vectors
        lay_normals(own)
        normal_text = f" + {normal.label}" if normal is not None else ""
        leg_laid = "".join(f" + {v.label}" for v in legs[k].vectors)
        polygon.step(Step(
            polygon=polygon.kind, kind="intersection",
            equation=f"{sym}_{labels[k]} = {sym}_{ref}{normal_text} + {first_term} = {leg_known(k)}{leg_laid} + "
                     f"{leg_term(k)}",
            result=labels[k].lower(),
            known=((f"{sym}_{ref}", "magnitude and direction"),
                   *((v.label, "magnitude and direction") for v in own),
                   (first_term, "direction"), (leg_term(k), "direction")),
            vectors=own,
            lines=(polygon.step_line((end, np.asarray(1j * r), None),
                                     f"{first_term} perpendicular to {ref_point}{point}"),
                   polygon.step_line((legs[k].through, legs[k].direction, None), line_label(k, leg_term(k)))),
            value=polygon.vec(built.tips[k]), topic="intersection", params=(("point", labels[k]),
                                                                            ("triad", _name(triad))),
            directions=(Direction(first_term, "perpendicular", f"{ref_point}{point}", ref.lower(),
                                  after=normal.label if normal is not None else ""),
                        leg_direction(k, leg_term(k), legs[k].vectors[-1].label if legs[k].vectors else ""))))


def _leg_line(which: str, leg: Leg, ternary: str) -> tuple[tuple[str, str], ...]:
    """A leg's line as data: a rod's own segment (``first_segment``, from ``first_pin`` to ``first_point``),
    the normal to a slide through a point (``first_slider``, ``first_point``), or the normal to the ternary's
    face through K (``first_face``, ``first_point``: the common normal of a flat-faced pair)."""
    if leg.kind == "pin":
        return ((f"{which}_segment", f"{leg.pin}{leg.point}"), (f"{which}_pin", str(leg.pin)),
                (f"{which}_point", leg.point))
    if leg.kind == "face":
        return ((f"{which}_face", ternary), (f"{which}_point", leg.point))
    assert leg.slider is not None
    return ((f"{which}_slider", leg.slider.name), (f"{which}_point", leg.point))


# -- acceleration -----------------------------------------------------------------------------------


def _acceleration_leg(ctx: AccelerationContext, triad: Triad, leg: Leg) -> _LegLine:
    b = ctx.b
    at = b.world(leg.point)
    if leg.drive is not None:
        return _LegLine(at, *driven_leg.acceleration_terms(ctx, leg))
    if leg.kind == "pin":
        assert leg.pin is not None
        omega = np.asarray(ctx.v.equivalent[leg.equivalent].real) if leg.equivalent else None
        (through, direction, _), normal, _ = ctx.normal_line(leg.known, leg.pin, leg.point, leg.link,
                                                             rigid=not leg.equivalent, omega=omega)
        return _LegLine(at, through, np.asarray(direction), (normal,) if normal is not None else ())
    start = b.tip(leg.known, leg.point)
    if leg.kind == "face":  # the point of T under K: a_K - 2 omega_T x v (the block's velocity over the face)
        coriolis = np.asarray(ctx.rules.coriolis * 2.0 * b.omega_of(triad.ternary)
                              * (1j * ctx.v.equivalent[leg.equivalent]))
        end = np.asarray(start - coriolis)
        laid = [DrawnVector(f"a^c_{b.label(triad.ternary, leg.point)}/{b.label(leg.known, leg.point)}",
                            b.vec(start), b.vec(end), "coriolis")] if b.record else []
        return _LegLine(at, end, _face_direction(b, leg), tuple(laid))
    assert leg.slider is not None
    if leg.kind == "slide":  # the block's point over the guide's: + 2 omega_guide x v_rel
        end, laid = ctx.lay_coriolis(leg.slider, start, leg.link, leg.known, leg.point)
    else:  # the point of T under K: a_K - 2 omega_T x v_rel (v_rel of the block over T)
        end, laid = ctx.lay_coriolis(leg.slider, start, leg.link, triad.ternary, leg.point, -1.0)
    return _LegLine(at, end, np.asarray(slide_direction(b.positions, leg.slider)), tuple(laid))


def acceleration_by_assur_point(ctx: AccelerationContext, triad: Triad) -> None:
    """The triad's acceleration polygon through its Assur point, after the known terms."""
    b = ctx.b
    legs = [_acceleration_leg(ctx, triad, leg) for leg in triad.legs]
    w = b.omega_of(triad.ternary)
    w2 = w * w
    def normal_t(r: Points) -> Points:
        return np.asarray(b.normal_sign * w2 * r)

    built, s_world, order = _construct(b, triad, legs, normal_t)
    _finish(b, triad, legs, built, s_world, order, normal_t)
    for leg, along, tip in zip(triad.legs, built.along, built.tips, strict=True):
        if leg.slider is not None:
            ctx.slide_values(leg.slider, leg.link, leg.point)
        if leg.drive is not None:
            driven_leg.finish_acceleration(ctx, leg, tip, along)
