"""A dyad's two assemblies as each assembly policy takes them (``engine.policy``): the dyad kind's answers.

- nearest the ``[guess]`` (a solve): the assembly whose points lie nearest the guess; where the guessed points
  of the dyad's own links do not tell the assemblies apart, each is carried through the later groups and the
  one that puts all guessed points nearest is kept; where nothing tells them apart, the documented default is
  taken with a ``default-assembly`` warning naming the other assembly and the guess that picks it;
- from the seed (a sweep): the seed row takes the solve's assembly and every other row follows it continuously
  (``engine.branches``);
- by label (a family): every member's seed row takes the label the scene's own solve takes, and follows it over
  the member's rows.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.branches import follow_branch, follow_members
from kinepoly.engine.closures import Choice, Closure, close_dyad
from kinepoly.engine.inputs import describe_input
from kinepoly.engine.placement import Placement
from kinepoly.engine.policy import Continuity, FamilyContinuity, NearestGuess, guess_coordinate
from kinepoly.errors import AssemblyError, KinepolyError, SingularityError
from kinepoly.geom.arrays import Reals
from kinepoly.geom.tolerances import ROUNDING_REL, SAME_REL
from kinepoly.geom.vec import Vec
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice

__all__ = ["DyadQuestion", "closing_error", "guess_distances"]


def closing_error(mechanism: Mechanism, closure: Closure) -> KinepolyError:
    """Why the dyad does not close at row 0 (a solve's one row): the group, the joint and the inequality."""
    name, where = closure.dyad.name, describe_input(mechanism)
    if closure.singular[0]:
        return SingularityError(f"singular position of group {name} at {where}: {closure.why(0)}")
    return AssemblyError(f"cannot assemble joint {closure.joint} of group {name} at {where}: {closure.why(0)}")


class DyadQuestion(Struct, frozen=True):
    """A dyad closed over rows (``closure``) and ``later``: its assembly ``k`` carried through the groups after it."""

    closure: Closure
    later: Callable[[int], Placement]

    # -- nearest the guess ----------------------------------------------------------------------------------------
    def by_guess(self, policy: NearestGuess, mechanism: Mechanism, placed: Placement) -> Choice | Placement:
        closure, later = self.closure, self.later
        own = [_score(policy, mechanism, closure.place(k)) for k in range(2)]
        tells = [complex(t[0]) for t in closure.telling]
        size = max(abs(t - tells[0]) for t in tells) + max(max(abs(t.real), abs(t.imag)) for t in tells)
        if max(own) - min(own) > ROUNDING_REL * size * size:
            return own.index(min(own))
        outcomes: list[tuple[float, Placement | None]] = []
        failure: AssemblyError | None = None
        for k in range(2):
            try:
                full = later(k)
                outcomes.append((_score(policy, mechanism, full.poses), full))
            except AssemblyError as error:
                failure = error
                outcomes.append((math.inf, None))
        scores = [o[0] for o in outcomes]
        finite = [x for x in scores if math.isfinite(x)]
        if len(finite) == 2 and max(scores) - min(scores) > ROUNDING_REL * size * size:
            best = outcomes[scores.index(min(scores))][1]
            assert best is not None
            return best
        if not finite and failure is not None:
            raise failure
        if len(finite) == 1 and failure is not None:  # only one assembly lets the rest of the mechanism close
            best = outcomes[scores.index(finite[0])][1]
            assert best is not None
            return best
        pick = 0 if outcomes[0][1] is not None else 1
        chosen = outcomes[pick][1]
        assert chosen is not None
        notice = _default_notice(policy, mechanism, closure, pick)
        before = len(placed.notices)
        return replace(chosen, notices=(*chosen.notices[:before], notice, *chosen.notices[before:]))

    # -- from the seed --------------------------------------------------------------------------------------------
    def by_seed(self, policy: Continuity, mechanism: Mechanism, placed: Placement) -> Choice | Placement:
        closure = self.closure
        label = _guessed(policy, mechanism, closure)
        if label is None:
            label = _seed_label(closure, policy.seed_poses(), policy.seed_row)
        labels = follow_branch(closure.telling[0], closure.telling[1], placed.ok, policy.seed_row, label,
                               policy.periodic, closure.gap)
        return labels if isinstance(labels, int) else np.asarray(labels == 0)

    # -- by label -------------------------------------------------------------------------------------------------
    def by_label(self, policy: FamilyContinuity, mechanism: Mechanism, placed: Placement) -> Choice | Placement:
        closure = self.closure
        seed = policy.seed
        own = close_dyad(policy.base, {link: ArrayPose.of_rows([pose]) for link, pose in seed.items()},
                         closure.dyad, policy.values)
        label = _seed_label(own, seed, 0)
        if closure.dyad.name in policy.flipped:
            label = 1 - label
        labels = follow_members(closure.telling[0], closure.telling[1], placed.ok, policy.rows_each, policy.seed_row,
                                label, policy.periodic, closure.gap)
        return labels if isinstance(labels, int) else np.asarray(labels == 0)


def _score(policy: NearestGuess, mechanism: Mechanism, poses: Mapping[str, ArrayPose]) -> float:
    return float(guess_distances(policy.guess, mechanism, poses)[0])


def guess_distances(guess: Mapping[str, Vec], mechanism: Mechanism, poses: Mapping[str, ArrayPose]) -> Reals:
    """At every row, the sum of the squared distances of the guessed points of the links ``poses`` places from their
    guess: what a solve (``NearestGuess``) weighs two assemblies by, the smaller taken."""
    total: Reals = np.zeros(len(next(iter(poses.values())).origin))
    for link, pose in poses.items():
        for point in mechanism.scene.link(link).points:
            if point.name in guess:
                g = guess[point.name]
                d = np.abs(pose.world(mechanism.local(link, point.name)) - complex(g[0], g[1]))
                total = total + d * d
    return total


def _default_notice(policy: NearestGuess, mechanism: Mechanism, closure: Closure, pick: int) -> Notice:
    origin = policy.origin
    point, chosen_at, other_at = _telling_point(mechanism, closure, pick)
    guess_x, guess_y = guess_coordinate(other_at.real, origin[0]), guess_coordinate(other_at.imag, origin[1])
    chosen_at, other_at = chosen_at + complex(*origin), other_at + complex(*origin)
    return Notice(
        "default-assembly",
        f"group {closure.dyad.name}: no [guess] tells its assemblies apart, so the default was taken: "
        f"{closure.labels[pick]}, which puts {point} at ({chosen_at.real:.6g}, {chosen_at.imag:.6g}); "
        f"the other assembly puts {point} at ({other_at.real:.6g}, {other_at.imag:.6g}) "
        f"(give [guess] {point} = [{guess_x}, {guess_y}] to take it)")


def _telling_point(mechanism: Mechanism, closure: Closure, pick: int) -> tuple[str, complex, complex]:
    """The point whose place differs most between the two assemblies: (name, chosen, other)."""
    chosen, other = closure.place(pick), closure.place(1 - pick)
    best = (closure.joint, complex(closure.telling[pick][0]), complex(closure.telling[1 - pick][0]))
    gap = abs(best[1] - best[2])
    for link, pose in chosen.items():
        for p in mechanism.scene.link(link).points:
            a, b = complex(pose.world(p.local)[0]), complex(other[link].world(p.local)[0])
            if abs(a - b) > gap * (1 + SAME_REL):
                best, gap = (p.name, a, b), abs(a - b)
    return best


def _guessed(policy: Continuity, mechanism: Mechanism, closure: Closure) -> int | None:
    """The seed row's assembly from the guess of the inner joint alone, where that decides it."""
    dyad, joint, row = closure.dyad, closure.joint, policy.seed_row
    if dyad.kind not in ("RRR", "RRP") or joint not in policy.guess or not closure.ok[row]:
        return None
    if any(p.name in policy.guess and p.name != joint
           for link in dyad.links for p in mechanism.scene.link(link).points):
        return None
    g = complex(*policy.guess[joint])
    tells = [complex(t[row]) for t in closure.telling]
    own = [abs(t - g) * abs(t - g) for t in tells]  # inf, not OverflowError, for a guess far out
    size = abs(tells[1] - tells[0]) + max(max(abs(t.real), abs(t.imag)) for t in tells)
    return own.index(min(own)) if abs(own[0] - own[1]) > ROUNDING_REL * size * size else None


def _seed_label(closure: Closure, seed: Mapping[str, LinkPose], row: int) -> int:
    """Which of the closure's assemblies at ``row`` the seed's poses are: the one whose telling point lies nearest
    the seed's."""
    target = closure.telling_at(dict(seed))
    gaps = [abs(complex(t[row]) - target) for t in closure.telling]
    return gaps.index(min(gaps))
