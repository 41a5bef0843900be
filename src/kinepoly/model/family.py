"""A family of mechanisms of one topology: the scene's mechanism with some points' coordinates given per member.

A family sweep (``kinepoly.sweep.family``) stacks its members' rows one member after another, ``rows_each``
rows each, so a point that differs between members has a coordinate per row: member k's value repeated over
its rows. ``FamilyMechanism.local`` returns those arrays where the scene's mechanism returns numbers; the
engine's arithmetic on a link's own coordinates (``model.array_pose.local_point``) is elementwise, so the
plan runs once for every member at once.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import cached_property

import numpy as np
from msgspec import field

from kinepoly.geom.arrays import Points, Reals
from kinepoly.geom.vec import Vec
from kinepoly.model.array_pose import local_point
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import SliderSpec

__all__ = ["FamilyMechanism", "RowPoint"]


class RowPoint(tuple[Reals, Reals]):
    """A point's own coordinates (x, y) at every row of a family, with x + iy (``rows``) made once."""

    rows: Points
    members: Points
    """x + iy, one per member."""
    rows_each: int

    @classmethod
    def of(cls, members: Points, rows_each: int) -> RowPoint:
        """The members' x + iy (one each), repeated over each member's rows."""
        rows = np.repeat(members, rows_each)
        point = cls((rows.real, rows.imag))
        point.rows, point.members, point.rows_each = rows, members, rows_each
        return point


class FamilyMechanism(Mechanism, frozen=True, eq=False, dict=True):
    """The scene's mechanism whose points ``varied`` (keyed (link, point), each member's x + iy) differ between
    the members, whose rows come ``rows_each`` to a member, every member over the same inputs."""

    varied: Mapping[tuple[str, str], Points] = field(default_factory=dict)
    rows_each: int = 1
    slides: Mapping[str, Points] = field(default_factory=dict)
    """The slide lines that differ between the members: each member's ``through`` (x + iy), keyed by slider."""
    shared_inputs: bool = True
    """Every member over the same inputs (a family sweep: one member's input rows are worked out and repeated);
    False where each row has an input of its own."""

    @cached_property
    def _rows(self) -> dict[tuple[str, str], RowPoint]:
        return {key: RowPoint.of(members, self.rows_each) for key, members in self.varied.items()}

    @cached_property
    def _slide_rows(self) -> dict[str, RowPoint]:
        return {name: RowPoint.of(members, self.rows_each) for name, members in self.slides.items()}

    def slide_through(self, slider: SliderSpec) -> Vec:
        """The slide line's ``through``: the scene's, or one per row where the members' lines differ."""
        found = self._slide_rows.get(slider.name)
        if found is not None:
            return found  # type: ignore[return-value]
        return slider.through

    def local(self, link: str, point: str) -> Vec:
        """Coordinates of ``point`` in ``link``'s own frame: numbers, or one per row where the point is varied
        (a ``RowPoint``, typed as the numbers it stands for row by row)."""
        found = self._rows.get((link, point))
        if found is not None:
            return found  # type: ignore[return-value]
        return super().local(link, point)

    @property
    def members(self) -> int:
        """How many members the family has."""
        return len(next(iter((*self.varied.values(), *self.slides.values()))))

    @staticmethod
    def _complex(local: Vec) -> complex:
        """x + iy of a point's own coordinates: one per row where the point is varied (``local_point``)."""
        return local_point(local)

    def member_local(self, link: str, point: str) -> Points:
        """``point``'s own coordinates in ``link`` as x + iy, one per member."""
        found = self.varied.get((link, point))
        if found is not None:
            return found
        return np.full(self.members, complex(*super().local(link, point)))

    def distance(self, link: str, a: str, b: str) -> float:
        """|ab| in ``link``'s own frame at every row where a or b is varied: worked out per member, then repeated."""
        key = (link, a, b)
        found = self._distances.get(key)
        if found is None:
            ends = [self.varied.get((link, p), complex(*super(FamilyMechanism, self).local(link, p))) for p in (a, b)]
            if all(isinstance(e, complex) for e in ends):
                return super().distance(link, a, b)
            found = self._distances[key] = np.repeat(np.abs(np.asarray(ends[1] - ends[0])), self.rows_each)
        return found  # type: ignore[return-value]

    @cached_property
    def _distances(self) -> dict[tuple[str, str, str], Reals]:
        return {}
