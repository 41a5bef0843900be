"""One assembly of a group closed by Newton's method, followed from row to row of a sweep.

Each row starts from the group's points one and two rows back, extrapolated. Where the row's solution
lies off that course (further from the extrapolation than ``ON_COURSE`` allows), Newton may have
closed the group in another assembly; where it does not close from there, the motion may be too quick
for the extrapolation. In both cases the walk goes from the last row to this one again in smaller steps
of the input (the known links' poses and the driven joints' values interpolated between the two rows),
halving a step that leaves the course. Where it comes through, the row takes the solution it reached
on the course. Where it does not (the course ends at a dead point between the two rows), the row is
marked, as are the rows after it, until one where the group does not close at all. Beyond such a gap
the walk resumes on the assembly whose Jacobian has the same sign (``RowClosure.sign``) as before it,
as a dyad resumes on the same side of its line (``engine.branches``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cached_property

from msgspec import Struct

from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.newton import RowClosure, group_reach, newton_row, start_poses
from kinepoly.engine.placement import Placement
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose

__all__ = ["ON_COURSE", "Walk", "known_points"]

ON_COURSE = (0.5, 0.02)
"""A solution is on the course within this share of the predicted step, plus this share of the group's
reach, from the extrapolation: Newton's solution from a course that turns or slows misses it by a little;
one in another assembly lies further off, by a good part of the links' length."""
_FINEST = 1.0 / 256
"""The smallest share of a row's step the walk tries before it takes the course to end between two rows."""


def known_points(mechanism: Mechanism, poses: Mapping[str, LinkPose]) -> dict[str, complex]:
    """The world place of every named point of the links in ``poses``."""
    return {p.name: complex(*pose.world(p.local)) for link, pose in poses.items()
            for p in mechanism.scene.link(link).points}


def _between(a: LinkPose, b: LinkPose, t: float) -> LinkPose:
    return LinkPose(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
                    a.theta + t * math.remainder(b.theta - a.theta, math.tau))


class Walk(Struct, dict=True):
    """One pass of the sweep over rows in order, from the seed row (``history``: its row and points)."""

    mechanism: Mechanism
    group: NewtonGroup
    placed: Placement
    size: float
    """The group's length scale for Newton's method (``engine.newton.group_size``)."""
    sign: int
    """The sign of the group's Jacobian on the assembly followed (0 while not known)."""
    history: list[tuple[int, dict[str, complex]]]
    """The last two rows taken, with the group's points there."""
    following: bool = True
    """False after a row where the group does not close at all: the next row that closes resumes."""

    @cached_property
    def reach(self) -> float:
        """The longest distance of a point of the group's links from the link's own origin."""
        return group_reach(self.mechanism, self.group, self.size)

    def gap(self) -> None:
        """A row where the group cannot be placed (an earlier group did not close there)."""
        self.following = False

    def row(self, row: int) -> tuple[dict[str, LinkPose] | None, bool]:
        """The group's poses at ``row`` on the assembly followed (None where it has none there), and whether the
        row closes only in another assembly (beyond a dead point)."""
        last_row, last = self.history[-1]
        guess = self._guess(row)
        closure = self._solve(self._known(row), guess, self.placed.row_values(row))
        adjacent = self.following and abs(row - last_row) == 1 and len(self.history) > 1
        if closure.poses is None and adjacent:
            closure = self._follow(row) or closure  # a motion too quick for the extrapolation: in smaller steps
        if closure.poses is None:
            self.following = False
            return None, False
        points = known_points(self.mechanism, closure.poses)
        if not self.following:
            if closure.sign * self.sign < 0:
                return None, True
            self._take(row, points, closure.sign)
            return closure.poses, False
        if abs(row - last_row) != 1:
            return None, True  # rows since the last one taken close only elsewhere: the course ended before them
        if len(self.history) > 1 and self._off_course(closure, guess, last):
            followed = self._follow(row)
            if followed is None or followed.poses is None:
                return None, True
            closure, points = followed, known_points(self.mechanism, followed.poses)
        self._take(row, points, closure.sign)
        return closure.poses, False

    def _take(self, row: int, points: dict[str, complex], sign: int) -> None:
        self.history = [*self.history[-1:], (row, points)]
        self.sign = sign or self.sign
        self.following = True

    def _guess(self, row: int) -> dict[str, complex]:
        """The points at ``row`` extrapolated from the last two rows taken (by one row's step at the most: beyond a
        gap the group is looked for near where it left off)."""
        last_row, last = self.history[-1]
        if len(self.history) == 1:
            return last
        before_row, before = self.history[-2]
        t = min(abs(row - last_row) / abs(last_row - before_row), 1.0)  # across a gap, one step at the most
        return {k: v + t * (v - before[k]) for k, v in last.items()}

    def _off_course(self, closure: RowClosure, guess: Mapping[str, complex], last: Mapping[str, complex]) -> bool:
        """Whether the solution lies off the course: further from the extrapolation than ``ON_COURSE`` allows, or,
        where its Jacobian's sign differs from the assembly's (a singular position passed: a change point
        on the course, or the other assembly where the two meet at a dead point), further than its first part."""
        assert closure.poses is not None
        points = known_points(self.mechanism, closure.poses)
        step = max(abs(v - last[k]) for k, v in guess.items())
        miss = max(abs(points[k] - v) for k, v in guess.items() if k in points)
        if closure.sign * self.sign < 0:
            return miss > ON_COURSE[0] * step
        return miss > ON_COURSE[0] * step + ON_COURSE[1] * self.reach

    def _known(self, row: int) -> dict[str, LinkPose]:
        return self.placed.row_poses(self.group.known_links(), row)

    def _solve(self, known: Mapping[str, LinkPose], guess: Mapping[str, complex],
               values: Mapping[int, float]) -> RowClosure:
        start, _ = start_poses(self.mechanism, self.group, {**guess, **known_points(self.mechanism, known)},
                               values)
        if start is None:
            return RowClosure(None, math.inf, 0)
        return newton_row(self.mechanism, self.group, known, start, self.size, values)

    def _follow(self, row: int) -> RowClosure | None:
        """From the last row taken to ``row`` in steps of the input small enough to stay on the course; None
        where the course ends between them."""
        a = self.history[-1][0]
        known_a, known_b = self._known(a), self._known(row)
        values_a, values_b = self.placed.row_values(a), self.placed.row_values(row)
        path = [(-1.0, self.history[-2][1]), (0.0, self.history[-1][1])]
        t, h, found = 0.0, 0.5, None
        while t < 1.0:
            h = min(h, 1.0 - t)
            (t0, p0), (t1, p1) = path[-2], path[-1]
            guess = {k: v + (v - p0[k]) * (t + h - t1) / (t1 - t0) for k, v in p1.items()}
            at = t + h
            known = known_b if at >= 1.0 else {k: _between(known_a[k], known_b[k], at) for k in known_a}
            values = values_b if at >= 1.0 else {k: v + at * (values_b[k] - v) for k, v in values_a.items()}
            closure = self._solve(known, guess, values)
            if closure.poses is not None and not self._off_course(closure, guess, p1):
                path.append((at, known_points(self.mechanism, closure.poses)))
                t, found, h = at, closure, min(2.0 * h, 0.5)
                continue
            h /= 2
            if h < _FINEST:
                return None
        return found
