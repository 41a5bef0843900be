"""Execute the position plan over an array of inputs: every dyad in its closed form, row by row at once.

Each dyad kind is the array twin of its scalar solver in ``solve.position`` (same circle-circle,
circle-line and line-line constructions, same touching tolerance). Where a dyad closes in two
ways, ``branches.follow_branch`` picks each row's assembly, starting from the seed row, whose
assembly is given (``solve_position`` at the scene's own input, as ``kinepoly solve`` picks it).
A group that is not a dyad is solved by ``solve.newton`` row after row (a loop, not
vectorised), each row started from the rows before it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from kinepoly.errors import AssemblyError, SingularityError
from kinepoly.geom.tolerances import ASSEMBLY_REL_TOL, NEAR_SINGULAR_SIN, PARALLEL_SIN, UNIT_ROUNDOFF
from kinepoly.model.mechanism import Joint, Mechanism, Revolute
from kinepoly.scene.spec import LinkInput, SliderInput, SliderSpec
from kinepoly.engine.plan import Dyad, NewtonGroup, PositionPlan
from kinepoly.model.pose import LinkPose
from kinepoly.engine.branches import follow_branch
from kinepoly.geom.arrays import (
    Bools,
    Points,
    Reals,
    circle_circle,
    circle_line,
    cross_lines,
    length,
    turn,
)
from kinepoly.model.array_pose import ArrayPose, pose_from_point, pose_from_two_points, still_pose

__all__ = ["Failure", "Names", "Progress", "SweepPositions", "seed_poses", "sweep_positions"]

Progress = Callable[[int, int], None]
"""Called with (rows done, rows in all) by the loops that take long (Newton groups)."""


@dataclass(frozen=True)
class Failure:
    """Rows where one group cannot be assembled (those where an earlier group failed are not among them)."""

    group: str
    joint: str
    rows: Bools
    why: Callable[[int], str]


class Names:
    """The scene's point names looked up once per sweep (the mechanism's lookups scan every link)."""

    def __init__(self, mechanism: Mechanism) -> None:
        self.points_of = {link.name: frozenset(link.point_names) for link in mechanism.scene.links}
        links_of: dict[str, list[str]] = {}
        for link in mechanism.scene.links:
            for p in link.points:
                links_of.setdefault(p.name, []).append(link.name)
        self.links_of = {point: tuple(links) for point, links in links_of.items()}

    def has_point(self, link: str, point: str) -> bool:
        return point in self.points_of[link]


@dataclass
class SweepPositions:
    """Poses of every link of the plan at every row; ``ok`` where all of them could be placed."""

    mechanism: Mechanism
    poses: dict[str, ArrayPose]
    ok: Bools
    failures: list[Failure] = field(default_factory=list)
    names: Names | None = None
    near: list[Failure] = field(default_factory=list)
    _points: dict[str, Points] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.names is None:
            self.names = Names(self.mechanism)

    def point(self, name: str) -> Points:
        """World position of a named point (through the first solved link that has it)."""
        found = self._points.get(name)
        if found is None:
            assert self.names is not None
            owner = next(link for link in self.names.links_of[name] if link in self.poses)
            found = self.poses[owner].world(self.mechanism.local(owner, name))
            self._points[name] = found
        return found

    def world(self, link: str, point: str) -> Points:
        return self.poses[link].world(self.mechanism.local(link, point))

    def scalar_poses(self, row: int) -> dict[str, LinkPose]:
        return {link: LinkPose(*pose.row(row)) for link, pose in self.poses.items()}


def _other(joint: Joint, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _local(mechanism: Mechanism, link: str, point: str) -> complex:
    x, y = mechanism.local(link, point)
    return complex(x, y)


def _c(v: tuple[float, float]) -> complex:
    return complex(v[0], v[1])


def slider_locus(mechanism: Mechanism, slider: SliderSpec, moving: str, local: tuple[float, float],
                 other: ArrayPose) -> tuple[Points, Points, Points]:
    """Rotation of the unknown side ``moving`` of a slider, and the line (through, direction) its
    point ``local`` runs on: ``solve.position.slider_locus`` over rows."""
    if moving == slider.block:
        rotation = other.rotation * turn(slider.angle_rad)
        through = other.world(slider.through)
        offset = rotation * (_c(local) - _local(mechanism, slider.block, slider.point))
        direction = rotation
    else:
        rotation = other.rotation * turn(-slider.angle_rad)
        through = other.world(mechanism.local(slider.block, slider.point))
        offset = rotation * (_c(local) - _c(slider.through))
        direction = other.rotation
    return rotation, through + offset, direction


Choice = int | Bools
"""Which assembly rows take: 0 or 1 for every row, or a mask of the rows that take assembly 0."""


def _pick(choice: Choice, first: Points, second: Points) -> Points:
    if isinstance(choice, int):
        return first if choice == 0 else second
    return np.asarray(np.where(choice, first, second))


@dataclass(frozen=True)
class _Closure:
    """A dyad solved over rows: the telling point of each assembly, where it closes, how to place it."""

    telling: tuple[Points, ...]
    ok: Bools
    gap: Reals | None
    place: Callable[[Choice], dict[str, ArrayPose]]
    telling_at: Callable[[dict[str, LinkPose]], complex]
    why: Callable[[int], str]
    joint: str
    near: Failure | None = None
    """Rows that close but are placed only roughly (the guide of an RPR dyad nearly on its pin)."""


def _link_size(mech: Mechanism) -> float:
    """The longest distance between two points of one link: the mechanism's own length scale."""
    return max((abs(complex(*p.local) - complex(*q.local)) for link in mech.scene.links for p in link.points
                for q in link.points), default=0.0)


def _closes(slack: Reals, scale: Reals | float) -> Bools:
    """The rows where a circle meets (or, within the tolerance of ``_touching``, just touches)."""
    return np.asarray(slack >= -ASSEMBLY_REL_TOL * scale * scale)


def _rrr(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> _Closure:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.second_joint, Revolute)
    assert isinstance(dyad.inner, Revolute)
    p1, p2, p3 = dyad.first_joint.point, dyad.inner.point, dyad.second_joint.point
    w1 = poses[_other(dyad.first_joint, i)].world(mech.local(_other(dyad.first_joint, i), p1))
    w3 = poses[_other(dyad.second_joint, j)].world(mech.local(_other(dyad.second_joint, j), p3))
    r1 = abs(_local(mech, i, p2) - _local(mech, i, p1))
    r2 = abs(_local(mech, j, p2) - _local(mech, j, p3))
    left, right, slack, d, h = circle_circle(w1, r1, w3, r2)
    ok = _closes(slack, np.maximum(d, max(r1, r2)))

    def place(choice: Choice) -> dict[str, ArrayPose]:
        at = _pick(choice, left, right)
        return {i: pose_from_two_points(mech.local(i, p1), mech.local(i, p2), w1, at, rigid=True),
                j: pose_from_two_points(mech.local(j, p3), mech.local(j, p2), w3, at, rigid=True)}

    def telling_at(scalar: dict[str, LinkPose]) -> complex:
        return _c(scalar[i].world(mech.local(i, p2)))

    def why(k: int) -> str:
        dk = float(d[k])
        if dk > r1 + r2:
            return f"|{p1} {p3}| = {dk:.6g} > |{p1}{p2}| + |{p2}{p3}| = {r1:.6g} + {r2:.6g} = {r1 + r2:.6g}"
        return f"|{p1} {p3}| = {dk:.6g} < | |{p1}{p2}| - |{p2}{p3}| | = {abs(r1 - r2):.6g}"

    return _Closure((left, right), ok, 2.0 * h, place, telling_at, why, p2)


def _rrp(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> _Closure:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
    slider = dyad.second_joint
    assert isinstance(slider, SliderSpec)
    p1, p2 = dyad.first_joint.point, dyad.inner.point
    w1 = poses[_other(dyad.first_joint, i)].world(mech.local(_other(dyad.first_joint, i), p1))
    r1 = abs(_local(mech, i, p2) - _local(mech, i, p1))
    rotation_j, through, direction = slider_locus(mech, slider, j, mech.local(j, p2), poses[_other(slider, j)])
    ahead, behind, slack, half = circle_line(w1, r1, through, direction)
    ok = _closes(slack, r1)

    def place(choice: Choice) -> dict[str, ArrayPose]:
        at = _pick(choice, ahead, behind)
        return {i: pose_from_two_points(mech.local(i, p1), mech.local(i, p2), w1, at, rigid=True),
                j: pose_from_point(mech.local(j, p2), at, rotation_j)}

    def telling_at(scalar: dict[str, LinkPose]) -> complex:
        return _c(scalar[i].world(mech.local(i, p2)))

    def why(k: int) -> str:
        h = math.sqrt(max(r1 * r1 - float(slack[k]), 0.0))
        return f"{p1} is {h:.6g} from the line {p2} runs on, more than |{p1}{p2}| = {r1:.6g}"

    return _Closure((ahead, behind), ok, 2.0 * half, place, telling_at, why, p2)


def _rpr(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> _Closure:
    slider = dyad.inner
    assert isinstance(slider, SliderSpec)
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.second_joint, Revolute)
    guide, block = slider.guide, slider.block
    outer = {dyad.first: dyad.first_joint, dyad.second: dyad.second_joint}
    pg, pb = outer[guide].point, outer[block].point
    wg = poses[_other(outer[guide], guide)].world(mech.local(_other(outer[guide], guide), pg))
    wb = poses[_other(outer[block], block)].world(mech.local(_other(outer[block], block), pb))
    pg_local = _local(mech, guide, pg)
    slide = turn(slider.angle_rad)
    offset = (_local(mech, block, pb) - _local(mech, block, slider.point)) * slide
    span = wb - wg
    r = length(span)
    ahead, behind, slack, _ = circle_line(pg_local, r, _c(slider.through) + offset, slide)
    # where pb lies on the guide's pivot the guide may take any angle: that row is not placed
    apart = r > ASSEMBLY_REL_TOL * (np.abs(wg) + np.abs(wb) + abs(pg_local) + abs(offset) + 1e-300)
    ok = _closes(slack, r) & apart
    unit_span = span / r

    def rotation(local_b: Points) -> Points:
        """theta_g = angle_of(wb - wg) - angle_of(local_b - pg_local), as a rotation."""
        rel = local_b - pg_local
        return np.asarray(unit_span * (rel / length(rel)).conjugate())

    u_ahead, u_behind = rotation(ahead), rotation(behind)

    def place(choice: Choice) -> dict[str, ArrayPose]:
        u = _pick(choice, u_ahead, u_behind)
        return {guide: pose_from_point(mech.local(guide, pg), wg, u),
                block: pose_from_point(mech.local(block, pb), wb, u * slide)}

    def telling_at(scalar: dict[str, LinkPose]) -> complex:
        theta = scalar[guide].theta
        w_g = _c(scalar[guide].world(mech.local(guide, pg)))
        w_b = _c(scalar[block].world(mech.local(block, pb)))
        return w_g + abs(w_b - w_g) * complex(math.cos(theta), math.sin(theta))

    def why(k: int) -> str:
        rk = float(r[k])
        if not apart[k]:
            return f"{pb} lies on {pg}, the pivot of the guide {guide}, so the guide's angle is not determined"
        h = math.sqrt(max(rk * rk - float(slack[k]), 0.0))
        return f"|{pg} {pb}| = {rk:.6g} is less than the offset {h:.6g} of slider {slider.name}'s line from {pg}"

    # Both assemblies put pb at wb; they differ in the guide's turn, told by wg + r e^(i theta_guide).
    # the guide's angle comes from the direction wg -> wb: when pb nears pg it is ill-conditioned
    size = max(abs(pg_local - _c(slider.through)), abs(offset), _link_size(mech))
    close = ok & (r < NEAR_SINGULAR_SIN * size)
    near = None
    if close.any():
        near = Failure(dyad.name, pb, close, lambda k: (
            f"near-singular: {pb} is {float(r[k]):.3g} from {pg}, the pivot of the guide {guide}, so the guide's "
            f"angle is uncertain by about {UNIT_ROUNDOFF * size / max(float(r[k]), 1e-300):.1g} rad"))
    return _Closure((wg + r * u_ahead, wg + r * u_behind), ok, None, place, telling_at, why, pb, near)


def _single(mech: Mechanism, poses: dict[str, ArrayPose], dyad: Dyad) -> _Closure:
    """PRP and RPP: the two slide lines cross in one point."""
    i, j = dyad.first, dyad.second
    second = dyad.second_joint
    assert isinstance(second, SliderSpec)
    if dyad.kind == "PRP":
        first = dyad.first_joint
        assert isinstance(first, SliderSpec) and isinstance(dyad.inner, Revolute)
        name = dyad.inner.point
        rotation_i, through_i, direction_i = slider_locus(mech, first, i, mech.local(i, name), poses[_other(first, i)])
        rotation_j, through_j, direction_j = slider_locus(mech, second, j, mech.local(j, name),
                                                          poses[_other(second, j)])
        crossing = cross_lines(through_i, direction_i, through_j, direction_j)
        lines = f"the lines of sliders {first.name} and {second.name} are parallel"

        def place(_: Choice) -> dict[str, ArrayPose]:
            return {i: pose_from_point(mech.local(i, name), crossing.point, rotation_i),
                    j: pose_from_point(mech.local(j, name), crossing.point, rotation_j)}
    else:
        inner = dyad.inner
        assert isinstance(dyad.first_joint, Revolute) and isinstance(inner, SliderSpec)
        p1 = dyad.first_joint.point
        w1 = poses[_other(dyad.first_joint, i)].world(mech.local(_other(dyad.first_joint, i), p1))
        point_j = mech.scene.link(j).points[0]
        name = point_j.name
        rotation_j, through_b, direction_b = slider_locus(mech, second, j, point_j.local, poses[_other(second, j)])
        rotation_i = rotation_j * turn(inner.angle_rad if i == inner.block else -inner.angle_rad)
        pose_i = pose_from_point(mech.local(i, p1), w1, rotation_i)
        _, through_a, direction_a = slider_locus(mech, inner, j, point_j.local, pose_i)
        crossing = cross_lines(through_a, direction_a, through_b, direction_b)
        lines = f"the lines of sliders {inner.name} and {second.name} are parallel"

        def place(_: Choice) -> dict[str, ArrayPose]:
            return {i: pose_i, j: pose_from_point(point_j.local, crossing.point, rotation_j)}

    ok = np.asarray(np.abs(crossing.sin_angle) > PARALLEL_SIN)
    return _Closure((crossing.point,), ok, None, place, lambda _: 0j, lambda _: lines, name)


_KINDS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _single, "RPP": _single}


def _driver_poses(mechanism: Mechanism, inputs: Reals) -> dict[str, ArrayPose]:
    """``solve.position._driver_poses`` over rows: ``inputs`` are theta (rad) or s (length)."""
    n = len(inputs)
    ground = mechanism.ground
    assert ground is not None
    poses = {ground: still_pose(n)}
    inp = mechanism.scene.input
    if isinstance(inp, LinkInput):
        pivot = mechanism.input_pivot().point
        world = np.full(n, _local(mechanism, ground, pivot))
        rotation = np.empty(n, np.complex128)
        rotation.real = np.cos(inputs)
        rotation.imag = np.sin(inputs)
        poses[inp.link] = pose_from_point(mechanism.local(inp.link, pivot), world, rotation)
    elif isinstance(inp, SliderInput):
        slider = mechanism.slider(inp.slider)
        direction = turn(slider.angle_rad)
        along = np.asarray(_c(slider.through) + inputs * direction, np.complex128)
        if slider.guide == ground:
            poses[slider.block] = pose_from_point(mechanism.local(slider.block, slider.point), along,
                                                  np.full(n, direction))
        else:
            block_point = np.full(n, _local(mechanism, ground, slider.point))
            poses[slider.guide] = ArrayPose(block_point - np.conjugate(direction) * along,
                                            np.full(n, np.conjugate(direction)))
    return poses


def _label_at_seed(closure: _Closure, seed_row: int, seed: dict[str, LinkPose]) -> int:
    target = closure.telling_at(seed)
    gaps = [abs(complex(t[seed_row]) - target) for t in closure.telling]
    return gaps.index(min(gaps))


def sweep_positions(mechanism: Mechanism, plan: PositionPlan, inputs: Reals, seed_row: int,
                    seed: dict[str, LinkPose], periodic: bool, progress: Progress | None = None) -> SweepPositions:
    """Poses of the plan's links at every input; row ``seed_row`` takes the assembly of ``seed``."""
    poses = _driver_poses(mechanism, inputs)
    ok = np.ones(len(inputs), np.bool_)
    failures: list[Failure] = []
    near: list[Failure] = []
    for group in plan.groups:
        if isinstance(group, NewtonGroup):
            from kinepoly.sweep.newton import newton_rows

            placed, own_ok = newton_rows(mechanism, group, poses, ok, seed_row, seed, progress)
            poses.update(placed)
            failures.append(Failure(group.name, "", ok & ~own_ok, _newton_why(group)))
            ok = ok & own_ok
            continue
        closure = _KINDS[group.kind](mechanism, poses, group)
        if closure.near is not None:
            near.append(closure.near)
        if not closure.ok.all():
            failures.append(Failure(group.name, closure.joint, ok & ~closure.ok, closure.why))
            ok = ok & closure.ok
        choice: Choice = 0
        if len(closure.telling) == 2:
            label = _label_at_seed(closure, seed_row, seed)
            labels = follow_branch(closure.telling[0], closure.telling[1], ok, seed_row, label, periodic, closure.gap)
            choice = labels if isinstance(labels, int) else np.asarray(labels == 0)
        poses.update(closure.place(choice))
    return SweepPositions(mechanism, poses, ok, failures, near=near)


def _newton_why(group: NewtonGroup) -> Callable[[int], str]:
    return lambda _: (f"Newton's method does not close group {group.name} from the rows before it "
                      "(the group cannot be assembled there)")


def seed_poses(mechanism: Mechanism, plan: PositionPlan) -> dict[str, LinkPose]:
    """The assembly ``kinepoly solve`` takes at the scene's own input."""
    from kinepoly.solve.position import solve_position

    try:
        return dict(solve_position(mechanism, plan).pose.links)
    except (AssemblyError, SingularityError) as error:
        raise type(error)(f"{error}; kinepoly sweep takes its assembly where kinepoly solve does, at the "
                          "scene's own input, so that input must be a position where the mechanism closes "
                          "in one definite way (change [input])") from error
