"""A group solved by Newton's method, started as each assembly policy takes it (``engine.policy``): the Newton
kind's answers.

- nearest the ``[guess]`` (a solve): Newton's method from the guess; where the solution lies off the guess it may
  have leapt to another assembly, and the one nearest the guess among those reached from starts about it is kept;
  further than ``_FAR_GUESS`` of the links' length from the guess, the solve says so (``far-from-guess``);
- from the seed (a sweep): each row from the rows before it, from the seed row forward and then backward
  (``engine.newton_walk``); a row that does not close, or closes only beyond a dead point, is marked;
- by label: a family with such a group is swept member by member (``sweep.family``), so this is not asked.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.cam_place import floating_unreachable
from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.inputs import describe_input
from kinepoly.engine.newton import RowClosure, group_reach, group_size, newton_row, start_poses
from kinepoly.engine.newton_walk import Walk, known_points
from kinepoly.engine.placement import Failure, Placement
from kinepoly.engine.policy import Continuity, FamilyContinuity, NearestGuess, guess_coordinate
from kinepoly.errors import AssemblyError
from kinepoly.geom.arrays import Reals
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice

__all__ = ["NewtonQuestion"]

_NEAR_GUESS = 0.03
"""A Newton group's solution with a guessed point further than this share of its links' length from its guess
may have leapt to another assembly: the solve looks for others about the guess and keeps the nearest (the
examples guess within 2.4%, and pay nothing for it)."""
_PROBES = 12
"""How many starts about the guess the solve tries besides it, where the first solution lies off the guess."""
_FAR_GUESS = 0.25
"""Further than this share from the guess, the solve says so (``far-from-guess``)."""


class NewtonQuestion(Struct, frozen=True):
    """A group placed by Newton's method: where each row starts."""

    group: NewtonGroup

    def by_guess(self, policy: NearestGuess, mechanism: Mechanism, placed: Placement) -> Placement:
        group = self.group
        known = known_points(mechanism, placed.row_poses(placed.poses, 0))
        points = {**{name: complex(x, y) for name, (x, y) in policy.guess.items()}, **known}
        start, missing = start_poses(mechanism, group, points, placed.row_values(0))
        if start is None:
            raise AssemblyError(
                f"group {group.name} is not a dyad and is solved by Newton's method from [guess]; "
                f"link {missing} has no guessed or known point: add [guess] positions for its points")
        size, reach = group_size(mechanism, group, points), group_reach(mechanism, group)
        known_poses, values = placed.row_poses(group.known_links(), 0), placed.row_values(0)
        closure = newton_row(mechanism, group, known_poses, start, size, values)
        off = _off_guess(policy, mechanism, closure.poses)
        if closure.poses is not None and off[0] > _NEAR_GUESS * reach:  # perhaps leapt to another assembly
            closure = _nearest(policy, mechanism, group, closure, (known_poses, start, size, values, reach))
            off = _off_guess(policy, mechanism, closure.poses)
        found, residual = closure.poses, closure.residual
        if found is None:
            raise AssemblyError(
                f"group {group.name} does not close at {describe_input(mechanism)}: Newton's method stopped with a "
                f"joint residual of {residual:.3g}; the group cannot be assembled there, or [guess] is far from it"
                f"{floating_unreachable(group)}")
        poses = {**placed.poses, **{link: ArrayPose.of_rows([pose]) for link, pose in found.items()}}
        if off[0] <= _FAR_GUESS * reach:
            return replace(placed, poses=poses)
        distance, point, at = off
        guess, origin = policy.guess[point], policy.origin
        at = at + complex(*origin)
        notice = Notice("far-from-guess", (
            f"group {group.name}: Newton's method from [guess] closed it where {point} lies at ({at.real:.6g}, "
            f"{at.imag:.6g}), {distance:.3g} {mechanism.scene.units.length} from its guess "
            f"[{guess_coordinate(guess[0], origin[0])}, {guess_coordinate(guess[1], origin[1])}]: another assembly "
            "may lie nearer the guess (give [guess] positions closer to the assembly you mean)"))
        return replace(placed, poses=poses, notices=(*placed.notices, notice))

    def by_seed(self, policy: Continuity, mechanism: Mechanism, placed: Placement) -> Placement:
        """Each row from the rows before it, from the seed row forward and then backward, on the seed's
        assembly (``engine.newton_walk``); a row that does not close, or closes only in another assembly
        beyond a dead point, is marked and skipped (with ``run_only``, the walk that way stops there)."""
        group, seed_row = self.group, policy.seed_row
        ok = placed.ok
        n = len(ok)
        origin = {link: np.zeros(n, np.complex128) for link in group.links}
        rotation = {link: np.ones(n, np.complex128) for link in group.links}
        closed = np.zeros(n, np.bool_)
        elsewhere = np.zeros(n, np.bool_)
        solved = policy.seed_poses()
        seed = {link: solved[link] for link in group.links}
        points = known_points(mechanism, seed)
        size = group_size(mechanism, group, points)
        seed_known = placed.row_poses(group.known_links(), seed_row)
        start, _ = start_poses(mechanism, group, {**points, **known_points(mechanism, seed_known)},
                               placed.row_values(seed_row))
        sign = 0 if start is None else newton_row(mechanism, group, seed_known, start, size,
                                                  placed.row_values(seed_row)).sign
        done = 0
        for order in (range(seed_row, n), range(seed_row - 1, -1, -1)):
            walk = Walk(mechanism, group, placed, size, sign, [(seed_row, points)])
            for row in order:
                done += 1
                if policy.progress is not None and done % 64 == 0:
                    policy.progress(done, n)
                if not ok[row]:
                    if policy.run_only:
                        break
                    walk.gap()
                    continue
                found, elsewhere[row] = (seed, False) if row == seed_row else walk.row(row)
                if found is None:
                    if policy.run_only:
                        break
                    continue
                for link, pose in found.items():
                    origin[link][row] = complex(pose.x, pose.y)
                    rotation[link][row] = complex(math.cos(pose.theta), math.sin(pose.theta))
                closed[row] = True
        if policy.progress is not None:
            policy.progress(n, n)
        poses = {**placed.poses, **{link: ArrayPose(origin[link], rotation[link]) for link in group.links}}
        failures = placed.failures
        if (ok & ~closed & ~elsewhere).any():
            failures = (*failures, Failure(group.name, "", ok & ~closed & ~elsewhere, lambda _: (
                f"Newton's method does not close group {group.name} from the rows before it "
                f"(the group cannot be assembled there){floating_unreachable(group)}")))
        if elsewhere.any():
            failures = (*failures, Failure(group.name, "", elsewhere, lambda _: (
                f"group {group.name} cannot be carried here from the rows before: its assembly meets a dead point "
                "on the way, and the group closes here only on the far side of it (the sweep resumes after the "
                "next rows where it does not close at all)")))
        return replace(placed, poses=poses, ok=ok & closed, failures=failures)

    def by_label(self, policy: FamilyContinuity, mechanism: Mechanism, placed: Placement) -> Placement:
        """Not asked: a family with a group solved by Newton's method is swept member by member."""
        raise AssertionError(f"group {self.group.name} is solved by Newton's method: its family is swept member by "
                             "member")


def _nearest(policy: NearestGuess, mechanism: Mechanism, group: NewtonGroup, closure: RowClosure,
             row: tuple[Mapping[str, LinkPose], Reals, float, Mapping[int, float], float]) -> RowClosure:
    """Of the assemblies Newton's method reaches from the guess (directly, creeping, and from ``_PROBES``
    starts turned and moved at random about it, the same every run), the one whose guessed points lie
    nearest their guess (least sum of squares, as for a dyad). A group that does not close from the guess
    is not searched further."""
    known, start, size, values, reach = row
    found = [closure, newton_row(mechanism, group, known, start, size, values, reach)]
    rng = np.random.default_rng(0)
    links = len(group.links)
    for _ in range(_PROBES):
        moved = start.copy()
        moved[:3 * links] += (rng.uniform(-0.5, 0.5, (links, 3)) * (reach, reach, 2.0 * math.pi)).ravel()
        found.append(newton_row(mechanism, group, known, moved, size, values))
    return min((c for c in found if c.poses is not None), key=lambda c: _score_poses(policy, mechanism, c.poses))


def _score_poses(policy: NearestGuess, mechanism: Mechanism, poses: Mapping[str, LinkPose] | None) -> float:
    # squared by multiplying: a guess at the edge of the floats gives inf, where ** 2 raises OverflowError
    return sum((d := abs(complex(*pose.world(p.local)) - complex(*policy.guess[p.name]))) * d
               for link, pose in (poses or {}).items() for p in mechanism.scene.link(link).points
               if p.name in policy.guess)


def _off_guess(policy: NearestGuess, mechanism: Mechanism,
               poses: Mapping[str, LinkPose] | None) -> tuple[float, str, complex]:
    """The guessed point of ``poses``' links furthest from its guess: (distance, name, where it lies)."""
    worst = (math.inf if poses is None else 0.0, "", 0j)
    for link, pose in (poses or {}).items():
        for p in mechanism.scene.link(link).points:
            if p.name in policy.guess:
                at = complex(*pose.world(p.local))
                distance = abs(at - complex(*policy.guess[p.name]))
                if distance > worst[0]:
                    worst = (distance, p.name, at)
    return worst
