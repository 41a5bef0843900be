"""Execute the position plan for one input: closed-form dyads, every assembly enumerated.

Each dyad gives two assemblies (one for PRP); the one nearest to the ``[guess]`` points is
taken. Without a guess that tells them apart the *default* is taken and a ``default-assembly``
warning names the other one. The default, documented in the README:

- RRR: the inner joint to the left of the line from the first link's outer joint to the
  second link's outer joint (the first link is the one listed first in ``[links]``);
- RRP, RPR, RPP: the inner joint further along the slide's direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from kinepoly.errors import AssemblyError, SingularityError
from kinepoly.geom import Line, circle_circle, circle_line, intersect, norm
from kinepoly.geom.tolerances import ASSEMBLY_REL_TOL
from kinepoly.geom.vec import Vec, add, angle_of, rotate, sub
from kinepoly.model.mechanism import Joint, Mechanism, Revolute
from kinepoly.notice import Notice
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput, SliderSpec
from kinepoly.solve.newton import solve_newton_group
from kinepoly.engine.plan import Dyad, NewtonGroup, PositionPlan
from kinepoly.model.pose import LinkPose, Pose

__all__ = ["PositionResult", "describe_input", "solve_position"]

IDENTITY = LinkPose(0.0, 0.0, 0.0)


@dataclass(frozen=True)
class PositionResult:
    pose: Pose
    notices: tuple[Notice, ...]


@dataclass(frozen=True)
class _Candidate:
    label: str
    poses: dict[str, LinkPose]
    point: str
    at: Vec


def describe_input(mechanism: Mechanism) -> str:
    """The input as a textbook names it: ``theta12 = 60 deg`` or ``s14 = 130 mm``."""
    scene = mechanism.scene
    inp = scene.input
    if isinstance(inp, LinkInput):
        value = math.degrees(inp.angle_rad) if scene.units.angle == "deg" else inp.angle_rad
        return f"theta{scene.ground}{inp.link} = {value:.15g} {scene.units.angle}"
    if isinstance(inp, SliderInput):
        return f"s{inp.slider} = {inp.s:.15g} {scene.units.length}"
    return "the given motion"


def pose_from_two_points(local_a: Vec, local_b: Vec, world_a: Vec, world_b: Vec) -> LinkPose:
    theta = angle_of(sub(world_b, world_a)) - angle_of(sub(local_b, local_a))
    return pose_from_point(local_a, world_a, theta)


def pose_from_point(local: Vec, world: Vec, theta: float) -> LinkPose:
    r = rotate(local, theta)
    return LinkPose(world[0] - r[0], world[1] - r[1], theta)


def _driver_poses(mechanism: Mechanism) -> dict[str, LinkPose]:
    ground = mechanism.ground
    if ground is None:
        return {mechanism.link_names[0]: IDENTITY}
    poses = {ground: IDENTITY}
    inp = mechanism.scene.input
    if isinstance(inp, LinkInput):
        pivot = mechanism.input_pivot().point
        world = mechanism.local(ground, pivot)
        poses[inp.link] = pose_from_point(mechanism.local(inp.link, pivot), world, inp.angle_rad)
    elif isinstance(inp, SliderInput):
        slider = mechanism.slider(inp.slider)
        direction = rotate((1.0, 0.0), slider.angle_rad)
        point_on_line = (slider.through[0] + inp.s * direction[0], slider.through[1] + inp.s * direction[1])
        if slider.guide == ground:
            poses[slider.block] = pose_from_point(mechanism.local(slider.block, slider.point), point_on_line,
                                                  slider.angle_rad)
        else:  # the block is the frame: place the guide so that the frame's point sits at s
            theta = -slider.angle_rad
            block_point = mechanism.local(ground, slider.point)
            along = (slider.through[0] + inp.s * math.cos(slider.angle_rad),
                     slider.through[1] + inp.s * math.sin(slider.angle_rad))
            poses[slider.guide] = pose_from_point(along, block_point, theta)
    return poses


def slider_locus(mechanism: Mechanism, slider: SliderSpec, moving: str, local: Vec,
                 other: LinkPose) -> tuple[float, Line]:
    """Angle of the unknown side ``moving`` of a slider and the line its point ``local`` runs on."""
    if moving == slider.block:
        theta = other.theta + slider.angle_rad
        through = other.world(slider.through)
        offset = rotate(sub(local, mechanism.local(slider.block, slider.point)), theta)
    else:
        theta = other.theta - slider.angle_rad
        through = other.world(mechanism.local(slider.block, slider.point))
        offset = rotate(sub(local, slider.through), theta)
    direction = rotate((1.0, 0.0), theta + (slider.angle_rad if moving != slider.block else 0.0))
    return theta, Line((through[0] + offset[0], through[1] + offset[1]), direction)


def _other(joint: Joint, link: str) -> str:
    if isinstance(joint, Revolute):
        return joint.other(link)
    return joint.guide if joint.block == link else joint.block


def _world(mechanism: Mechanism, poses: dict[str, LinkPose], link: str, point: str) -> Vec:
    return poses[link].world(mechanism.local(link, point))


def _no_assembly(dyad: Dyad, mechanism: Mechanism, joint: str, why: str) -> AssemblyError:
    return AssemblyError(
        f"cannot assemble joint {joint} of group {dyad.name} at {describe_input(mechanism)}: {why}"
    )


def _touching(slack: float, scale: float) -> float:
    return 0.0 if -ASSEMBLY_REL_TOL * scale * scale <= slack < 0.0 else slack


def _rrr(dyad: Dyad, mechanism: Mechanism, poses: dict[str, LinkPose]) -> list[_Candidate]:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.second_joint, Revolute)
    assert isinstance(dyad.inner, Revolute)
    p1, p2, p3 = dyad.first_joint.point, dyad.inner.point, dyad.second_joint.point
    w1 = _world(mechanism, poses, _other(dyad.first_joint, i), p1)
    w3 = _world(mechanism, poses, _other(dyad.second_joint, j), p3)
    r1 = norm(sub(mechanism.local(i, p2), mechanism.local(i, p1)))
    r2 = norm(sub(mechanism.local(j, p2), mechanism.local(j, p3)))
    d = norm(sub(w3, w1))
    if d <= ASSEMBLY_REL_TOL * max(r1, r2):
        raise SingularityError(
            f"singular position of group {dyad.name} at {describe_input(mechanism)}: the pins {p1} and {p3} "
            f"coincide (|{p1} {p3}| = {d:.3g}), so {p2} may lie anywhere on a circle of radius {r1:.6g} about "
            "them (a change point of the linkage)")
    left, right, slack = circle_circle(w1, r1, w3, r2)
    slack = _touching(slack, max(r1, r2, d))
    if slack < 0.0:
        if d > r1 + r2:
            why = f"|{p1} {p3}| = {d:.6g} > |{p1}{p2}| + |{p2}{p3}| = {r1:.6g} + {r2:.6g} = {r1 + r2:.6g}"
        else:
            why = f"|{p1} {p3}| = {d:.6g} < | |{p1}{p2}| - |{p2}{p3}| | = {abs(r1 - r2):.6g}"
        raise _no_assembly(dyad, mechanism, p2, why)
    out = []
    for label, at in ((f"{p2} left of {p1}->{p3}", left), (f"{p2} right of {p1}->{p3}", right)):
        out.append(_Candidate(label, {
            i: pose_from_two_points(mechanism.local(i, p1), mechanism.local(i, p2), w1, at),
            j: pose_from_two_points(mechanism.local(j, p3), mechanism.local(j, p2), w3, at),
        }, p2, at))
    return out


def _rrp(dyad: Dyad, mechanism: Mechanism, poses: dict[str, LinkPose]) -> list[_Candidate]:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.inner, Revolute)
    assert isinstance(dyad.second_joint, SliderSpec)
    p1, p2 = dyad.first_joint.point, dyad.inner.point
    w1 = _world(mechanism, poses, _other(dyad.first_joint, i), p1)
    r1 = norm(sub(mechanism.local(i, p2), mechanism.local(i, p1)))
    other = poses[_other(dyad.second_joint, j)]
    theta_j, line = slider_locus(mechanism, dyad.second_joint, j, mechanism.local(j, p2), other)
    ahead, behind, slack = circle_line(w1, r1, line)
    slack = _touching(slack, r1)
    if slack < 0.0:
        h = math.sqrt(r1 * r1 - slack)
        raise _no_assembly(dyad, mechanism, p2, f"{p1} is {h:.6g} from the line {p2} runs on, "
                           f"more than |{p1}{p2}| = {r1:.6g}")
    out = []
    for label, at in ((f"{p2} ahead along slider {dyad.second_joint.name}", ahead),
                      (f"{p2} behind along slider {dyad.second_joint.name}", behind)):
        out.append(_Candidate(label, {
            i: pose_from_two_points(mechanism.local(i, p1), mechanism.local(i, p2), w1, at),
            j: pose_from_point(mechanism.local(j, p2), at, theta_j),
        }, p2, at))
    return out


def _rpr(dyad: Dyad, mechanism: Mechanism, poses: dict[str, LinkPose]) -> list[_Candidate]:
    slider = dyad.inner
    assert isinstance(slider, SliderSpec)
    assert isinstance(dyad.first_joint, Revolute) and isinstance(dyad.second_joint, Revolute)
    guide, block = slider.guide, slider.block
    outer = {dyad.first: dyad.first_joint, dyad.second: dyad.second_joint}
    pg, pb = outer[guide].point, outer[block].point
    wg = _world(mechanism, poses, _other(outer[guide], guide), pg)
    wb = _world(mechanism, poses, _other(outer[block], block), pb)
    pg_local = mechanism.local(guide, pg)
    offset = rotate(sub(mechanism.local(block, pb), mechanism.local(block, slider.point)), slider.angle_rad)
    locus = Line((slider.through[0] + offset[0], slider.through[1] + offset[1]), rotate((1.0, 0.0), slider.angle_rad))
    r = norm(sub(wb, wg))
    if r <= ASSEMBLY_REL_TOL * norm(sub(mechanism.local(block, pb), mechanism.local(block, slider.point))) or r == 0.0:
        raise SingularityError(
            f"singular position of group {dyad.name} at {describe_input(mechanism)}: the pins {pg} and {pb} "
            f"coincide, so the direction of slider {slider.name} is not determined (a change point)")
    ahead, behind, slack = circle_line(pg_local, r, locus)
    slack = _touching(slack, r)
    if slack < 0.0:
        h = math.sqrt(r * r - slack)
        raise _no_assembly(dyad, mechanism, pb, f"|{pg} {pb}| = {r:.6g} is less than the offset {h:.6g} "
                           f"of slider {slider.name}'s line from {pg}")
    out = []
    for label, local_b in ((f"{pb} ahead along slider {slider.name}", ahead),
                           (f"{pb} behind along slider {slider.name}", behind)):
        theta_g = angle_of(sub(wb, wg)) - angle_of(sub(local_b, pg_local))
        out.append(_Candidate(label, {
            guide: pose_from_point(pg_local, wg, theta_g),
            block: pose_from_point(mechanism.local(block, pb), wb, theta_g + slider.angle_rad),
        }, pb, LinkPose(0, 0, theta_g).world(sub(local_b, pg_local))))
    return out


def _prp(dyad: Dyad, mechanism: Mechanism, poses: dict[str, LinkPose]) -> list[_Candidate]:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, SliderSpec) and isinstance(dyad.second_joint, SliderSpec)
    assert isinstance(dyad.inner, Revolute)
    p = dyad.inner.point
    ti, li = slider_locus(mechanism, dyad.first_joint, i, mechanism.local(i, p), poses[_other(dyad.first_joint, i)])
    tj, lj = slider_locus(mechanism, dyad.second_joint, j, mechanism.local(j, p), poses[_other(dyad.second_joint, j)])
    crossing = intersect(li, lj)
    if not crossing.is_finite:
        raise _no_assembly(dyad, mechanism, p, f"the lines of sliders {dyad.first_joint.name} and "
                           f"{dyad.second_joint.name} are parallel")
    at = crossing.point
    return [_Candidate(f"{p} where the slides cross", {
        i: pose_from_point(mechanism.local(i, p), at, ti),
        j: pose_from_point(mechanism.local(j, p), at, tj),
    }, p, at)]


def _rpp(dyad: Dyad, mechanism: Mechanism, poses: dict[str, LinkPose]) -> list[_Candidate]:
    i, j = dyad.first, dyad.second
    assert isinstance(dyad.first_joint, Revolute)
    assert isinstance(dyad.inner, SliderSpec) and isinstance(dyad.second_joint, SliderSpec)
    p1 = dyad.first_joint.point
    w1 = _world(mechanism, poses, _other(dyad.first_joint, i), p1)
    point_j = mechanism.scene.link(j).points[0]
    theta_j, _ = slider_locus(mechanism, dyad.second_joint, j, point_j.local, poses[_other(dyad.second_joint, j)])
    theta_i = theta_j + (dyad.inner.angle_rad if i == dyad.inner.block else -dyad.inner.angle_rad)
    pose_i = pose_from_point(mechanism.local(i, p1), w1, theta_i)
    _, la = slider_locus(mechanism, dyad.inner, j, point_j.local, pose_i)
    _, lb = slider_locus(mechanism, dyad.second_joint, j, point_j.local, poses[_other(dyad.second_joint, j)])
    crossing = intersect(la, lb)
    if not crossing.is_finite:
        raise _no_assembly(dyad, mechanism, point_j.name, f"the lines of sliders {dyad.inner.name} and "
                           f"{dyad.second_joint.name} are parallel")
    at = crossing.point
    return [_Candidate(f"{point_j.name} where the slides cross",
                       {i: pose_i, j: pose_from_point(point_j.local, at, theta_j)}, point_j.name, at)]


_SOLVERS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}


def _guess_score(mechanism: Mechanism, poses: dict[str, LinkPose], guess: dict[str, Vec]) -> float:
    total = 0.0
    for link, pose in poses.items():
        for point in mechanism.scene.link(link).points:
            if point.name in guess:
                w = pose.world(point.local)
                total += (w[0] - guess[point.name][0]) ** 2 + (w[1] - guess[point.name][1]) ** 2
    return total


def _telling_point(mechanism: Mechanism, candidates: list[_Candidate]) -> tuple[str, Vec, Vec]:
    """The point whose place differs most between the first two assemblies."""
    first, second = candidates[0], candidates[1]
    best = (candidates[0].point, first.at, second.at)
    gap = norm(sub(first.at, second.at))
    for link, pose in first.poses.items():
        for p in mechanism.scene.link(link).points:
            a, b = pose.world(p.local), second.poses[link].world(p.local)
            if norm(sub(a, b)) > gap * (1 + 1e-9):
                best, gap = (p.name, a, b), norm(sub(a, b))
    return best


def _solve_groups(mechanism: Mechanism, groups: tuple[Dyad | NewtonGroup, ...], poses: dict[str, LinkPose],
                  guess: dict[str, Vec], origin: Vec = (0.0, 0.0)) -> tuple[dict[str, LinkPose], list[Notice]]:
    """Solve ``groups`` in order. Where the guessed points of a dyad's own links do not tell its
    assemblies apart, each assembly is carried through the later groups and the one that puts
    all guessed points nearest to their guesses is kept. ``origin`` is added to positions in
    messages (the solve may run in a frame local to the mechanism)."""
    poses = dict(poses)
    notices: list[Notice] = []
    for index, group in enumerate(groups):
        if isinstance(group, NewtonGroup):
            poses.update(solve_newton_group(mechanism, group, poses, guess, describe_input(mechanism)))
            continue
        candidates = _SOLVERS[group.kind](group, mechanism, poses)
        if len(candidates) == 1:
            poses.update(candidates[0].poses)
            continue
        own = [_guess_score(mechanism, c.poses, guess) for c in candidates]
        size = max(norm(sub(c.at, candidates[0].at)) for c in candidates) + max(abs(v) for c in candidates
                                                                               for v in c.at)
        if max(own) - min(own) > 1e-12 * size * size:
            poses.update(candidates[own.index(min(own))].poses)
            continue
        rest = groups[index + 1:]
        outcomes: list[tuple[float, dict[str, LinkPose], list[Notice]]] = []
        failure: AssemblyError | None = None
        for cand in candidates:
            try:
                full, later = _solve_groups(mechanism, rest, {**poses, **cand.poses}, guess, origin)
                outcomes.append((_guess_score(mechanism, full, guess), full, later))
            except AssemblyError as error:
                failure = error
                outcomes.append((math.inf, {}, []))
        scores = [o[0] for o in outcomes]
        finite = [x for x in scores if math.isfinite(x)]
        if len(finite) == len(scores) and max(scores) - min(scores) > 1e-12 * size * size:
            best = outcomes[scores.index(min(scores))]
            return {**poses, **best[1]}, notices + best[2]
        if not finite:
            assert failure is not None
            raise failure
        if len(finite) == 1:  # only one assembly lets the rest of the mechanism close
            best = outcomes[scores.index(finite[0])]
            return {**poses, **best[1]}, notices + best[2]
        pick = 0 if math.isfinite(scores[0]) else 1
        point, chosen_at, other_at = _telling_point(mechanism, candidates)
        if pick == 1:
            chosen_at, other_at = other_at, chosen_at
        guess_x, guess_y = _coordinate(other_at[0], origin[0]), _coordinate(other_at[1], origin[1])
        chosen_at, other_at = add(chosen_at, origin), add(other_at, origin)
        notices.append(Notice(
            "default-assembly",
            f"group {group.name}: no [guess] tells its assemblies apart, so the default was taken: "
            f"{candidates[pick].label}, which puts {point} at ({chosen_at[0]:.6g}, {chosen_at[1]:.6g}); "
            f"the other assembly puts {point} at ({other_at[0]:.6g}, {other_at[1]:.6g}) "
            f"(give [guess] {point} = [{guess_x}, {guess_y}] to take it)"))
        return {**poses, **outcomes[pick][1]}, notices + outcomes[pick][2]
    return poses, notices


def _coordinate(local: float, origin: float) -> str:
    """A coordinate to 4 significant digits of the mechanism's own size, wherever the mechanism is."""
    if origin == 0.0:
        return f"{local:.4g}"
    decimals = max(0, 3 - math.floor(math.log10(abs(local)))) if local != 0.0 else 2
    return f"{local + origin:.{decimals}f}"


def solve_position(mechanism: Mechanism, plan: PositionPlan, origin: Vec = (0.0, 0.0)) -> PositionResult:
    """Poses of the driven links and of every group in the plan, for the scene's input.

    ``origin``: where the mechanism's frame origin lies in the user's frame, for messages.
    """
    poses = _driver_poses(mechanism)
    if isinstance(mechanism.scene.input, GivenInput):
        return PositionResult(Pose(poses), ())
    solved, notices = _solve_groups(mechanism, plan.groups, poses, dict(mechanism.scene.guess), origin)
    return PositionResult(Pose(solved), tuple(notices))
