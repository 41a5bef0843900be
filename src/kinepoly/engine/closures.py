"""Each dyad closed in its closed form over rows, every assembly returned.

A dyad's closure is where its two unknown links meet: two circles (RRR), a circle and a line
(RRP, RPR), two lines (PRP, RPP). The closure returns every assembly (two, or one where two
slides cross) with its *telling point* (the inner joint, whose place tells the assemblies apart)
at every row, the rows where the dyad closes at all, and how to place the links for a choice of
assembly. Choosing is not done here: that is an assembly policy (``engine.assembly``).

Where a row does not close, ``why(row)`` says why with the inequality that fails; where it is
singular (two pins that should span the dyad coincide: a change point), ``singular`` marks it.

The default assembly, documented in the README:

- RRR: the inner joint to the left of the line from the first link's outer joint to the
  second link's outer joint (the first link is the one listed first in ``[links]``);
- RRP, RPR, RPP: the inner joint further along the slide's direction.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from msgspec import Struct, field

from kinepoly.engine.carry import carried_local, relative_turn
from kinepoly.engine.groups import Dyad
from kinepoly.geom.arrays import Bools, Points, Reals, circle_circle, circle_line, cross_lines, length, turn
from kinepoly.geom.tolerances import ASSEMBLY_REL_TOL, NEAR_SINGULAR_SIN, PARALLEL_SIN, TINY_POSITIVE, UNIT_ROUNDOFF
from kinepoly.model.array_pose import ArrayPose, local_point, pose_at, pose_from_point, pose_from_two_points
from kinepoly.model.mechanism import Joint, Mechanism, Revolute
from kinepoly.model.pose import LinkPose
from kinepoly.scene.spec import SliderSpec

__all__ = ["Choice", "Closure", "close_dyad", "other_side", "pick", "slider_locus"]

Choice = int | Bools
"""Which assembly rows take: an index for every row, or a mask of the rows that take assembly 0."""


def pick(choice: Choice, first: Points, second: Points) -> Points:
    if isinstance(choice, int):
        return first if choice == 0 else second
    return np.asarray(np.where(choice, first, second))


class Closure(Struct, frozen=True):
    """A dyad closed over rows.

    ``telling``: each assembly's telling point at every row; ``labels``: each assembly in words
    (for the default-assembly warning); ``ok``: rows where the dyad closes; ``singular``: rows
    where it is at a change point (a subset of ``~ok``); ``gap``: the distance between the two
    assemblies' telling points where it is known in closed form; ``place_rows``: the links' poses
    for a choice; ``why``: why a row does not close; ``joint``: the joint named in messages;
    ``telling_at``: the telling point of the dyad placed by scalar poses (which assembly they are);
    ``near``: rows that close but are placed only roughly, with why.
    """

    dyad: Dyad
    telling: tuple[Points, ...]
    labels: tuple[str, ...]
    ok: Bools
    singular: Bools
    gap: Reals | None
    place_rows: Callable[[Choice], dict[str, ArrayPose]]
    why: Callable[[int], str]
    joint: str
    telling_at: Callable[[dict[str, LinkPose]], complex]
    near: tuple[Bools, Callable[[int], str]] | None = None
    _placed: dict[int, dict[str, ArrayPose]] = field(default_factory=dict)

    def place(self, choice: Choice) -> dict[str, ArrayPose]:
        """The links' poses for ``choice``; one assembly for every row is placed once (a policy that
        weighs both assemblies, and the executor that then places the chosen one, share it)."""
        if not isinstance(choice, int):
            return self.place_rows(choice)
        if choice not in self._placed:
            self._placed[choice] = self.place_rows(choice)
        return self._placed[choice]


def other_side(joint: Joint, link: str) -> str:
    """The link on the other side of ``joint`` from ``link``."""
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _local(mechanism: Mechanism, link: str, point: str) -> complex:
    return mechanism.local_at(link, point)


def _c(v: tuple[float, float]) -> complex:
    return local_point(v)


def _row(value: Reals | float, k: int) -> float:
    """Row ``k`` of a dimension that is one number, or one per row in a family (``model.family``)."""
    return float(value[k]) if isinstance(value, np.ndarray) else float(value)


def _outer_world(mech: Mechanism, poses: dict[str, ArrayPose], joint: Joint, link: str, point: str) -> Points:
    known = other_side(joint, link)
    return poses[known].world_at(mech.local_at(known, point))


def slider_locus(mechanism: Mechanism, slider: SliderSpec, moving: str, local: tuple[float, float],
                 other: ArrayPose) -> tuple[Points, Points, Points]:
    """Rotation of the unknown side ``moving`` of a slider, and the line (through, direction) that
    its point ``local`` runs on, the other side's pose being ``other``."""
    if moving == slider.block:
        rotation = other.rotation * turn(slider.angle_rad)
        through = other.world(mechanism.slide_through(slider))
        offset = rotation * (_c(local) - _local(mechanism, slider.block, slider.point))
        direction = rotation
    else:
        rotation = other.rotation * turn(-slider.angle_rad)
        through = other.world(mechanism.local(slider.block, slider.point))
        offset = rotation * (_c(local) - _c(mechanism.slide_through(slider)))
        direction = other.rotation
    return np.asarray(rotation), np.asarray(through + offset), np.asarray(direction)


def _inner_at(mech: Mechanism, link: str, point: str) -> Callable[[dict[str, LinkPose]], complex]:
    return lambda scalar: _c(scalar[link].world(mech.local(link, point)))


def _largest(*values: Reals | float) -> Reals | float:
    """The largest of some lengths: numbers, or arrays where a family's dimensions vary by row."""
    for value in values:
        if isinstance(value, np.ndarray) and value.ndim:
            return np.asarray(np.maximum.reduce(np.broadcast_arrays(*values)))
    return max(values)


def _closes(slack: Reals, scale: Reals | float) -> Bools:
    """The rows where a circle meets (or, within ``ASSEMBLY_REL_TOL``, just touches) the other curve."""
    return np.asarray(slack >= -ASSEMBLY_REL_TOL * scale * scale)


def _rrr(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad, values: tuple[Reals, ...] = ()) -> Closure:
    """Two circles. A carried dyad's first side is its carrier and ``first`` held by a driven joint: the
    inner joint lies at a distance from the carrier's outer joint that the input fixes at each row."""
    i, j, outer, drive = dyad.first, dyad.second, dyad.outer_first, dyad.drive
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.second_joint, Revolute)
    assert isinstance(dyad.inner, Revolute)
    p1, p2, p3 = dyad.first_joint.point, dyad.inner.point, dyad.second_joint.point
    known1, known3 = dyad.first_joint.other(outer), dyad.second_joint.other(j)
    w1 = poses[known1].world_at(mech.local_at(known1, p1))
    w3 = poses[known3].world_at(mech.local_at(known3, p3))
    local2: complex | Points = mech.local_at(i, p2)
    if drive is not None:  # the inner joint in the carrier's frame, row by row
        local2 = carried_local(mech, drive, i, mech.local_at(i, p2), values[drive.index])
    span = local2 - mech.local_at(outer, p1)
    r1 = np.abs(span)  # numpy's modulus, not the hypot of Python's abs: they differ in the last bit
    r2 = abs(mech.local_at(j, p2) - mech.local_at(j, p3))
    left, right, slack, d, h = circle_circle(w1, r1, w3, r2)
    # one number (as Python's max finds it), or per row where a driven joint or a family's members vary a length
    longer = max(r1, r2) if isinstance(r1, float) and isinstance(r2, float) else np.maximum(r1, r2)
    apart = np.asarray(d > ASSEMBLY_REL_TOL * longer)
    singular = np.invert(apart)
    ok = _closes(slack, np.maximum(d, longer))
    ok &= apart  # closes, and not singular
    if not isinstance(r1, float) or not r1 > 0:
        ok &= r1 > 0

    def place(choice: Choice) -> dict[str, ArrayPose]:
        at = pick(choice, left, right)
        rotation = np.asarray((at - w1) * (np.conjugate(span) / (r1 * r1)))
        placed = {outer: pose_at(mech.local_at(outer, p1), w1, rotation),
                  j: pose_from_two_points(mech.local(j, p3), mech.local(j, p2), w3, at, rigid=True)}
        if drive is not None:
            placed[i] = pose_from_point(mech.local(i, p2), at, np.asarray(rotation * relative_turn(
                drive, i, values[drive.index])))
        return placed

    def why(k: int) -> str:
        dk, rk, r2k = float(d[k]), _row(r1, k), _row(r2, k)
        held = f" (|{p1}{p2}| as links {outer} and {i} are held by {drive.name})" if drive else ""
        if rk == 0.0:
            return f"the input puts {p2} on {p1}, so link {j}'s pin {p2} has no circle to run on"
        if singular[k]:
            return (f"the pins {p1} and {p3} coincide (|{p1} {p3}| = {dk:.3g}), so {p2} may lie anywhere on a "
                    f"circle of radius {rk:.6g} about them (a change point of the linkage)")
        if dk > rk + r2k:
            return f"|{p1} {p3}| = {dk:.6g} > |{p1}{p2}| + |{p2}{p3}| = {rk:.6g} + {r2k:.6g} = {rk + r2k:.6g}{held}"
        return (f"|{p1} {p3}| = {dk:.6g} < | |{p1}{p2}| - |{p2}{p3}| | = | {rk:.6g} - {r2k:.6g} | = "
                f"{abs(rk - r2k):.6g}{held}")

    labels = (f"{p2} left of {p1}->{p3}", f"{p2} right of {p1}->{p3}")
    return Closure(dyad, (left, right), labels, ok, singular, 2.0 * h, place, why, p2, _inner_at(mech, i, p2))


def _rrp(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> Closure:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
    slider = dyad.second_joint
    assert isinstance(slider, SliderSpec)
    p1, p2 = dyad.first_joint.point, dyad.inner.point
    w1 = _outer_world(mech, poses, dyad.first_joint, i, p1)
    r1 = abs(_local(mech, i, p2) - _local(mech, i, p1))
    rotation_j, through, direction = slider_locus(mech, slider, j, mech.local(j, p2), poses[other_side(slider, j)])
    ahead, behind, slack, half = circle_line(w1, r1, through, direction)
    ok = _closes(slack, r1)

    def place(choice: Choice) -> dict[str, ArrayPose]:
        at = pick(choice, ahead, behind)
        return {i: pose_from_two_points(mech.local(i, p1), mech.local(i, p2), w1, at, rigid=True),
                j: pose_from_point(mech.local(j, p2), at, rotation_j)}

    def why(k: int) -> str:
        r1k = _row(r1, k)
        h = math.sqrt(max(r1k * r1k - float(slack[k]), 0.0))
        return f"{p1} is {h:.6g} from the line {p2} runs on, more than |{p1}{p2}| = {r1k:.6g}"

    labels = (f"{p2} ahead along slider {slider.name}", f"{p2} behind along slider {slider.name}")
    return Closure(dyad, (ahead, behind), labels, ok, np.zeros_like(ok), 2.0 * half, place, why, p2,
                   _inner_at(mech, i, p2))


def _rpr(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> Closure:
    slider = dyad.inner
    assert isinstance(slider, SliderSpec)
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.second_joint, Revolute)
    guide, block = slider.guide, slider.block
    outer = {dyad.first: dyad.first_joint, dyad.second: dyad.second_joint}
    pg, pb = outer[guide].point, outer[block].point
    wg = _outer_world(mech, poses, outer[guide], guide, pg)
    wb = _outer_world(mech, poses, outer[block], block, pb)
    pg_local = _local(mech, guide, pg)
    slide = turn(slider.angle_rad)
    offset = (_local(mech, block, pb) - _local(mech, block, slider.point)) * slide
    span = wb - wg
    r = length(span)
    through = _c(mech.slide_through(slider))
    ahead, behind, slack, _ = circle_line(pg_local, r, through + offset, slide)
    # where pb lies on the guide's pivot the guide may take any angle: a change point
    singular = np.asarray(~(r > ASSEMBLY_REL_TOL
                            * (np.abs(wg) + np.abs(wb) + abs(pg_local) + abs(offset) + TINY_POSITIVE)))
    ok = _closes(slack, r) & ~singular
    unit_span = span / r

    def rotation(local_b: Points) -> Points:
        """theta_guide = angle_of(wb - wg) - angle_of(local_b - pg_local), as a rotation."""
        rel = local_b - pg_local
        return np.asarray(unit_span * (rel / length(rel)).conjugate())

    u_ahead, u_behind = rotation(ahead), rotation(behind)

    def place(choice: Choice) -> dict[str, ArrayPose]:
        u = pick(choice, u_ahead, u_behind)
        return {guide: pose_from_point(mech.local(guide, pg), wg, u),
                block: pose_from_point(mech.local(block, pb), wb, u * slide)}

    def why(k: int) -> str:
        rk = float(r[k])
        if singular[k]:
            return (f"the pins {pg} and {pb} coincide, so the direction of slider {slider.name} is not "
                    "determined (a change point)")
        h = math.sqrt(max(rk * rk - float(slack[k]), 0.0))
        return f"|{pg} {pb}| = {rk:.6g} is less than the offset {h:.6g} of slider {slider.name}'s line from {pg}"

    # the guide's angle comes from the direction wg -> wb: when pb nears pg it is ill-conditioned
    size = _largest(abs(pg_local - through), abs(offset), mech.link_size)
    close = ok & (r < NEAR_SINGULAR_SIN * size)
    near = None
    if close.any():
        near = (close, lambda k: (
            f"near-singular: {pb} is {float(r[k]):.3g} from {pg}, the pivot of the guide {guide}, so the guide's "
            f"angle is uncertain by about {UNIT_ROUNDOFF * _row(size, k) / max(float(r[k]), TINY_POSITIVE):.1g} rad"))
    labels = (f"{pb} ahead along slider {slider.name}", f"{pb} behind along slider {slider.name}")
    # both assemblies put pb at wb; they differ in the guide's turn, told by wg + r e^(i theta_guide)
    def telling_at(scalar: dict[str, LinkPose]) -> complex:
        theta = scalar[guide].theta
        w_g = _c(scalar[guide].world(mech.local(guide, pg)))
        w_b = _c(scalar[block].world(mech.local(block, pb)))
        return w_g + abs(w_b - w_g) * complex(math.cos(theta), math.sin(theta))

    return Closure(dyad, (wg + r * u_ahead, wg + r * u_behind), labels, ok, singular, None, place, why, pb,
                   telling_at, near)


def _two_slides(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> Closure:
    """PRP and RPP: the two slide lines cross in one point."""
    i, j = dyad.first, dyad.second
    second = dyad.second_joint
    assert isinstance(second, SliderSpec)
    if dyad.kind == "PRP":
        first = dyad.first_joint
        assert isinstance(first, SliderSpec) and isinstance(dyad.inner, Revolute)
        name = dyad.inner.point
        rotation_i, through_i, direction_i = slider_locus(mech, first, i, mech.local(i, name),
                                                          poses[other_side(first, i)])
        rotation_j, through_j, direction_j = slider_locus(mech, second, j, mech.local(j, name),
                                                          poses[other_side(second, j)])
        crossing = cross_lines(through_i, direction_i, through_j, direction_j)
        lines = f"the lines of sliders {first.name} and {second.name} are parallel"

        def place(_: Choice) -> dict[str, ArrayPose]:
            return {i: pose_from_point(mech.local(i, name), crossing.point, rotation_i),
                    j: pose_from_point(mech.local(j, name), crossing.point, rotation_j)}
    else:
        inner = dyad.inner
        assert isinstance(dyad.first_joint, Revolute) and isinstance(inner, SliderSpec)
        p1 = dyad.first_joint.point
        w1 = _outer_world(mech, poses, dyad.first_joint, i, p1)
        point_j = mech.scene.link(j).points[0]
        name = point_j.name
        rotation_j, through_b, direction_b = slider_locus(mech, second, j, mech.local(j, name),
                                                          poses[other_side(second, j)])
        rotation_i = rotation_j * turn(inner.angle_rad if i == inner.block else -inner.angle_rad)
        pose_i = pose_from_point(mech.local(i, p1), w1, rotation_i)
        _, through_a, direction_a = slider_locus(mech, inner, j, mech.local(j, name), pose_i)
        crossing = cross_lines(through_a, direction_a, through_b, direction_b)
        lines = f"the lines of sliders {inner.name} and {second.name} are parallel"

        def place(_: Choice) -> dict[str, ArrayPose]:
            return {i: pose_i, j: pose_from_point(mech.local(j, name), crossing.point, rotation_j)}

    ok = np.asarray(np.abs(crossing.sin_angle) > PARALLEL_SIN)
    return Closure(dyad, (crossing.point,), (f"{name} where the slides cross",), ok, np.zeros_like(ok), None, place,
                   lambda _: lines, name, lambda _: 0j)


_KINDS = {"RRP": _rrp, "RPR": _rpr, "PRP": _two_slides, "RPP": _two_slides}


def close_dyad(mechanism: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad,
               values: tuple[Reals, ...] = ()) -> Closure:
    """Every assembly of ``dyad`` at every row, its known links placed by ``poses`` (``values``: each
    input's value at every row, for a carried dyad)."""
    if dyad.kind == "RRR":
        return _rrr(mechanism, poses, dyad, values)
    return _KINDS[dyad.kind](mechanism, poses, dyad)
