"""Assembly policies: which of a group's assemblies each row takes, and what a row that fails means.

Two policies answer the executor (``engine.position``):

- ``NearestGuess``, for a solve (a batch of one row): the assembly whose points lie nearest the
  ``[guess]``. Where the guessed points of a dyad's own links do not tell its assemblies apart,
  each assembly is carried through the later groups and the one that puts all guessed points
  nearest is kept; where nothing tells them apart, the documented default is taken with a
  ``default-assembly`` warning naming the other assembly and the guess that picks it. A group
  that does not close raises ``AssemblyError`` (``SingularityError`` at a change point), naming
  the group, the joint and the inequality. Newton groups start from the ``[guess]``.
- ``Continuity``, for a sweep: the seed row takes the solve's assembly and every other row
  follows it continuously (``engine.branches``); rows that do not close are marked, not raised.
  Newton groups start each row from the rows before it, extrapolated.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from kinepoly.engine.branches import follow_branch, follow_members
from kinepoly.engine.cam_contact import Candidates, Ints
from kinepoly.engine.cam_place import floating_unreachable, follow_contact, guessed_contact, seeded_contact
from kinepoly.engine.closures import Choice, Closure
from kinepoly.engine.groups import CamGroup, NewtonGroup, PositionPlan
from kinepoly.engine.newton import RowClosure, group_reach, group_size, newton_row, start_poses
from kinepoly.engine.newton_walk import Walk, known_points
from kinepoly.engine.position import Failure, Placement, Positions, describe_input, input_values, solve_positions
from kinepoly.errors import AssemblyError, SingularityError
from kinepoly.geom.arrays import Bools, Reals
from kinepoly.geom.tolerances import ROUNDING_REL, SAME_REL
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice
from kinepoly.scene.flat_side import flat_side

__all__ = ["Continuity", "FamilyContinuity", "NearestGuess", "position_at_input", "seed_labels"]

Vec = tuple[float, float]

_NEAR_GUESS = 0.03
"""A Newton group's solution with a guessed point further than this share of its links' length from its guess
may have leapt to another assembly: the solve looks for others about the guess and keeps the nearest (the
examples guess within 2.4%, and pay nothing for it)."""
_PROBES = 12
"""How many starts about the guess the solve tries besides it, where the first solution lies off the guess."""
_FAR_GUESS = 0.25
"""Further than this share from the guess, the solve says so (``far-from-guess``)."""


@dataclass(frozen=True)
class NearestGuess:
    """The solve's policy (row 0 of a batch of one): nearest the ``[guess]``, with look-ahead."""

    guess: Mapping[str, Vec]
    origin: Vec = (0.0, 0.0)
    """Where the mechanism's frame origin lies in the user's frame, for messages."""

    def _score(self, mechanism: Mechanism, poses: Mapping[str, ArrayPose]) -> float:
        total = 0.0
        for link, pose in poses.items():
            for point in mechanism.scene.link(link).points:
                if point.name in self.guess:
                    at = complex(pose.world(point.local)[0])
                    g = self.guess[point.name]
                    d = abs(at - complex(g[0], g[1]))
                    total += d * d
        return total

    def failed(self, mechanism: Mechanism, closure: Closure, rows: Bools) -> None:
        name, where = closure.dyad.name, describe_input(mechanism)
        if closure.singular[0]:
            raise SingularityError(f"singular position of group {name} at {where}: {closure.why(0)}")
        raise AssemblyError(f"cannot assemble joint {closure.joint} of group {name} at {where}: {closure.why(0)}")

    def contact(self, mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """The contact that puts the follower's guessed points nearest their guess."""
        return guessed_contact(mechanism, group, candidates, self.guess)

    def unreachable(self, message: str) -> None:
        raise AssemblyError(message)

    def choose(self, mechanism: Mechanism, closure: Closure, placed: Placement,
               later: Callable[[int], Placement]) -> Choice | Placement:
        own = [self._score(mechanism, closure.place(k)) for k in range(2)]
        tells = [complex(t[0]) for t in closure.telling]
        size = max(abs(t - tells[0]) for t in tells) + max(max(abs(t.real), abs(t.imag)) for t in tells)
        if max(own) - min(own) > ROUNDING_REL * size * size:
            return own.index(min(own))
        outcomes: list[tuple[float, Placement | None]] = []
        failure: AssemblyError | None = None
        for k in range(2):
            try:
                full = later(k)
                outcomes.append((self._score(mechanism, full.poses), full))
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
        notice = self._default_notice(mechanism, closure, pick)
        before = len(placed.notices)
        return replace(chosen, notices=(*chosen.notices[:before], notice, *chosen.notices[before:]))

    def _default_notice(self, mechanism: Mechanism, closure: Closure, pick: int) -> Notice:
        point, chosen_at, other_at = _telling_point(mechanism, closure, pick)
        guess_x, guess_y = _coordinate(other_at.real, self.origin[0]), _coordinate(other_at.imag, self.origin[1])
        chosen_at, other_at = chosen_at + complex(*self.origin), other_at + complex(*self.origin)
        return Notice(
            "default-assembly",
            f"group {closure.dyad.name}: no [guess] tells its assemblies apart, so the default was taken: "
            f"{closure.labels[pick]}, which puts {point} at ({chosen_at.real:.6g}, {chosen_at.imag:.6g}); "
            f"the other assembly puts {point} at ({other_at.real:.6g}, {other_at.imag:.6g}) "
            f"(give [guess] {point} = [{guess_x}, {guess_y}] to take it)")

    def newton(self, mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
        known = known_points(mechanism, placed.row_poses(placed.poses, 0))
        points = {**{name: complex(x, y) for name, (x, y) in self.guess.items()}, **known}
        start, missing = start_poses(mechanism, group, points, placed.row_values(0))
        if start is None:
            raise AssemblyError(
                f"group {group.name} is not a dyad and is solved by Newton's method from [guess]; "
                f"link {missing} has no guessed or known point: add [guess] positions for its points")
        size, reach = group_size(mechanism, group, points), group_reach(mechanism, group)
        known_poses, values = placed.row_poses(group.known_links(), 0), placed.row_values(0)
        closure = newton_row(mechanism, group, known_poses, start, size, values)
        off = self._off_guess(mechanism, closure.poses)
        if closure.poses is not None and off[0] > _NEAR_GUESS * reach:  # perhaps leapt to another assembly
            closure = self._nearest(mechanism, group, closure, (known_poses, start, size, values, reach))
            off = self._off_guess(mechanism, closure.poses)
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
        guess = self.guess[point]
        at = at + complex(*self.origin)
        notice = Notice("far-from-guess", (
            f"group {group.name}: Newton's method from [guess] closed it where {point} lies at ({at.real:.6g}, "
            f"{at.imag:.6g}), {distance:.3g} {mechanism.scene.units.length} from its guess "
            f"[{_coordinate(guess[0], self.origin[0])}, {_coordinate(guess[1], self.origin[1])}]: another assembly "
            "may lie nearer the guess (give [guess] positions closer to the assembly you mean)"))
        return replace(placed, poses=poses, notices=(*placed.notices, notice))

    def _nearest(self, mechanism: Mechanism, group: NewtonGroup, closure: RowClosure,
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
        return min((c for c in found if c.poses is not None), key=lambda c: self._score_poses(mechanism, c.poses))

    def _score_poses(self, mechanism: Mechanism, poses: Mapping[str, LinkPose] | None) -> float:
        # squared by multiplying: a guess at the edge of the floats gives inf, where ** 2 raises OverflowError
        return sum((d := abs(complex(*pose.world(p.local)) - complex(*self.guess[p.name]))) * d
                   for link, pose in (poses or {}).items() for p in mechanism.scene.link(link).points
                   if p.name in self.guess)

    def _off_guess(self, mechanism: Mechanism, poses: Mapping[str, LinkPose] | None) -> tuple[float, str, complex]:
        """The guessed point of ``poses``' links furthest from its guess: (distance, name, where it lies)."""
        worst = (math.inf if poses is None else 0.0, "", 0j)
        for link, pose in (poses or {}).items():
            for p in mechanism.scene.link(link).points:
                if p.name in self.guess:
                    at = complex(*pose.world(p.local))
                    distance = abs(at - complex(*self.guess[p.name]))
                    if distance > worst[0]:
                        worst = (distance, p.name, at)
        return worst


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


def _coordinate(local: float, origin: float) -> str:
    """A coordinate to 4 significant digits of the mechanism's own size, wherever the mechanism is."""
    if origin == 0.0:
        return f"{local:.4g}"
    decimals = max(0, 3 - math.floor(math.log10(abs(local)))) if local != 0.0 else 2
    return f"{local + origin:.{decimals}f}"


@dataclass(frozen=True)
class Continuity:
    """The sweep's policy: row ``seed_row`` takes the assembly of ``seed``; the others follow it.

    ``seed`` is the solve's positions at the seed row, or a function that solves them when asked:
    with ``guess``, a dyad whose inner joint is the only guessed point of its links takes, at the
    seed row, the assembly that puts the joint nearest its guess, as ``NearestGuess`` would, without
    solving the seed row apart; anything else asks for the seed.
    """

    seed_row: int
    seed: Mapping[str, LinkPose] | Callable[[], Mapping[str, LinkPose]]
    periodic: bool
    progress: Callable[[int, int], None] | None = None
    guess: Mapping[str, Vec] = field(default_factory=dict)

    def _seed(self) -> Mapping[str, LinkPose]:
        return self.seed() if callable(self.seed) else self.seed

    def _guessed(self, mechanism: Mechanism, closure: Closure) -> int | None:
        """The seed row's assembly from the guess of the inner joint alone, where that decides it."""
        dyad, joint, row = closure.dyad, closure.joint, self.seed_row
        if dyad.kind not in ("RRR", "RRP") or joint not in self.guess or not closure.ok[row]:
            return None
        if any(p.name in self.guess and p.name != joint
               for link in dyad.links for p in mechanism.scene.link(link).points):
            return None
        g = complex(*self.guess[joint])
        tells = [complex(t[row]) for t in closure.telling]
        own = [abs(t - g) * abs(t - g) for t in tells]  # inf, not OverflowError, for a guess far out
        size = abs(tells[1] - tells[0]) + max(max(abs(t.real), abs(t.imag)) for t in tells)
        return own.index(min(own)) if abs(own[0] - own[1]) > ROUNDING_REL * size * size else None

    def failed(self, mechanism: Mechanism, closure: Closure, rows: Bools) -> None:
        """Rows that do not close are marked by the executor; nothing to raise."""

    def unreachable(self, message: str) -> None:
        """Rows where a cam's follower cannot touch are marked by the executor; nothing to raise."""

    def contact(self, mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """The seed row's contact (where the solve puts W), followed by continuity."""
        if not candidates.found[self.seed_row].any():
            return follow_contact(candidates, self.seed_row, 0), ()
        seed = seeded_contact(mechanism, group, candidates, self.seed_row, self._seed())
        return follow_contact(candidates, self.seed_row, seed), ()

    def choose(self, mechanism: Mechanism, closure: Closure, placed: Placement,
               later: Callable[[int], Placement]) -> Choice | Placement:
        label = self._guessed(mechanism, closure)
        if label is None:
            label = _seed_label(closure, self._seed(), self.seed_row)
        labels = follow_branch(closure.telling[0], closure.telling[1], placed.ok, self.seed_row, label,
                               self.periodic, closure.gap)
        return labels if isinstance(labels, int) else np.asarray(labels == 0)

    def newton(self, mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
        """Each row from the rows before it, from the seed row forward and then backward, on the seed's
        assembly (``engine.newton_walk``); a row that does not close, or closes only in another assembly
        beyond a dead point, is marked and skipped."""
        ok = placed.ok
        n = len(ok)
        origin = {link: np.zeros(n, np.complex128) for link in group.links}
        rotation = {link: np.ones(n, np.complex128) for link in group.links}
        closed = np.zeros(n, np.bool_)
        elsewhere = np.zeros(n, np.bool_)
        solved = self._seed()
        seed = {link: solved[link] for link in group.links}
        points = known_points(mechanism, seed)
        size = group_size(mechanism, group, points)
        seed_known = placed.row_poses(group.known_links(), self.seed_row)
        start, _ = start_poses(mechanism, group, {**points, **known_points(mechanism, seed_known)},
                               placed.row_values(self.seed_row))
        sign = 0 if start is None else newton_row(mechanism, group, seed_known, start, size,
                                                  placed.row_values(self.seed_row)).sign
        done = 0
        for order in (range(self.seed_row, n), range(self.seed_row - 1, -1, -1)):
            walk = Walk(mechanism, group, placed, size, sign, [(self.seed_row, points)])
            for row in order:
                done += 1
                if self.progress is not None and done % 64 == 0:
                    self.progress(done, n)
                if not ok[row]:
                    walk.gap()
                    continue
                found, elsewhere[row] = (seed, False) if row == self.seed_row else walk.row(row)
                if found is None:
                    continue
                for link, pose in found.items():
                    origin[link][row] = complex(pose.x, pose.y)
                    rotation[link][row] = complex(math.cos(pose.theta), math.sin(pose.theta))
                closed[row] = True
        if self.progress is not None:
            self.progress(n, n)
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


def _seed_label(closure: Closure, seed: Mapping[str, LinkPose], row: int) -> int:
    """Which of the closure's assemblies at ``row`` the seed's poses are: the one whose telling point lies nearest
    the seed's."""
    target = closure.telling_at(dict(seed))
    gaps = [abs(complex(t[row]) - target) for t in closure.telling]
    return gaps.index(min(gaps))


@dataclass(frozen=True)
class _Labelling:
    """Places the seed's own assembly again (one row), noting each dyad's label: ``seed_labels``."""

    seed: Mapping[str, LinkPose]
    labels: dict[str, int]

    def choose(self, mechanism: Mechanism, closure: Closure, placed: Placement,
               later: Callable[[int], Placement]) -> Choice | Placement:
        label = self.labels[closure.dyad.name] = _seed_label(closure, self.seed, 0)
        return label

    def newton(self, mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
        """A Newton group has no labelled assemblies: its seed poses are taken as they are."""
        poses = {link: ArrayPose.of_rows([self.seed[link]]) for link in group.links}
        return replace(placed, poses={**placed.poses, **poses})

    def failed(self, mechanism: Mechanism, closure: Closure, rows: Bools) -> None:
        """The seed closes (it was solved): nothing fails."""

    def unreachable(self, message: str) -> None:
        """The seed closes (it was solved): nothing fails."""

    def contact(self, mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        return np.array([seeded_contact(mechanism, group, candidates, 0, self.seed)]), ()


def seed_labels(mechanism: Mechanism, plan: PositionPlan, seed: Mapping[str, LinkPose]) -> dict[str, int]:
    """Each dyad's assembly in ``seed`` (the solve's at the scene's own input) by its label, the index of
    ``Closure.telling``: 0 the inner joint left of the line between the outer joints (RRR) or further along the
    slide (RRP, RPR, RPP), 1 the other. The same label is the same assembly in every member of a family."""
    labels: dict[str, int] = {}
    with np.errstate(all="ignore"):
        solve_positions(mechanism, plan, input_values(mechanism), _Labelling(seed, labels))
    return labels


@dataclass(frozen=True)
class FamilyContinuity:
    """A family's policy (``model.family``; its rows are the members' rows, ``rows_each`` each, one member after
    another): every member's row ``seed_row`` takes the assembly of the label the scene's own solve takes
    (``seed_labels``), and the member's other rows follow it continuously (``engine.branches.follow_members``).

    A family is solved in one batch where its groups are dyads, carried dyads and drive groups; a mechanism
    with cams, gears or groups solved by Newton's method is swept member by member (``sweep.family``), so the
    questions only those ask are not put to this policy."""

    seed_row: int
    rows_each: int
    labels: Mapping[str, int]
    periodic: bool

    def choose(self, mechanism: Mechanism, closure: Closure, placed: Placement,
               later: Callable[[int], Placement]) -> Choice | Placement:
        labels = follow_members(closure.telling[0], closure.telling[1], placed.ok, self.rows_each, self.seed_row,
                                self.labels[closure.dyad.name], self.periodic, closure.gap)
        return labels if isinstance(labels, int) else np.asarray(labels == 0)

    def failed(self, mechanism: Mechanism, closure: Closure, rows: Bools) -> None:
        """Rows that do not close are marked by the executor; nothing to raise."""

    def unreachable(self, message: str) -> None:
        """Not asked: a family with cams is swept member by member."""
        raise AssertionError(message)

    def newton(self, mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
        """Not asked: a family with Newton groups is swept member by member."""
        raise AssertionError(f"group {group.name} is solved by Newton's method: its family is swept member by member")

    def contact(self, mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """Not asked: a family with cams is swept member by member."""
        raise AssertionError(f"group {group.name}: a family with cams is swept member by member")


def position_at_input(mechanism: Mechanism, plan: PositionPlan, origin: Vec = (0.0, 0.0)) -> Positions:
    """The positions at the scene's own input (a batch of one row), the assembly nearest the ``[guess]``.

    ``origin``: where the mechanism's frame origin lies in the user's frame, for messages.
    """
    with np.errstate(all="ignore"):  # a row that does not close raises by name
        found = solve_positions(mechanism, plan, input_values(mechanism), NearestGuess(dict(mechanism.scene.guess),
                                                                                       origin))
    return replace(found, notices=(*found.notices, *_untold_flat_sides(mechanism)))


def _untold_flat_sides(mechanism: Mechanism) -> list[Notice]:
    """A ``default-assembly`` warning for each circle cam's flat face whose side the ``[guess]`` does not tell
    (``scene.flat_side``: the disc was put on the face's left)."""
    scene = mechanism.scene
    return [Notice("default-assembly", f"cam {cam.name}: no [guess] tells which side of follower {cam.follower}'s flat "
                   f"face the disc touches, so the default was taken: the disc on the face's left; give [guess] "
                   f"positions of a point of the follower and of the cam (or two of the follower's) with the disc's "
                   f"centre on the side you mean")
            for cam in scene.cams if cam.kind == "flat" and not cam.is_spline and flat_side(scene, cam) is None]
