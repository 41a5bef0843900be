"""A sweep's result: its columns (one reported quantity at every row) and each row's status.

The values a sweep returns, apart from the code that fills them (``sweep.run``, ``sweep.columns``) and the
code that shows them (``sweep.table``, ``sweep.plots``; a notebook shows a result as its plots, set by the
package's face).
"""

from __future__ import annotations

from functools import cached_property
from typing import Literal, NamedTuple

import numpy as np
import numpy.typing as npt
from msgspec import Struct, field

from kinepoly.engine.position import Positions
from kinepoly.geom.arrays import Bools, Reals
from kinepoly.notice import Notice
from kinepoly.scene.spec import Scene

__all__ = ["CANNOT_ASSEMBLE", "NEAR_SINGULAR", "OK", "ORDER", "SINGULAR", "STATUS", "Column", "Follower", "Kind",
           "SweepResult"]

STATUS = ("ok", "near-singular", "singular", "cannot-assemble")
"""Row status by level: a row's level is the worst thing that happened to it."""

OK, NEAR_SINGULAR, SINGULAR, CANNOT_ASSEMBLE = range(4)
"""The levels of ``STATUS``, the values of ``SweepResult.status``."""

Kind = Literal["input", "angle", "omega", "alpha", "position", "velocity", "acceleration", "slider",
               "slider-rate", "slider-acceleration", "coriolis", "centrode", "centrode-local", "transmission",
               "pressure", "ratio", "series-error", "series-rate-error", "series-acceleration-error"]
ORDER = {"input": -1, "angle": 0, "position": 0, "slider": 0, "transmission": 0, "omega": 1, "velocity": 1,
          "slider-rate": 1, "centrode": 1, "centrode-local": 1, "alpha": 2, "acceleration": 2,
          "slider-acceleration": 2, "coriolis": 2, "pressure": 0, "ratio": 1, "series-error": 0, "series-rate-error": 1,
          "series-acceleration-error": 2}
"""The order of the transmission function each kind of column belongs to: 0 position, 1 velocity, 2 acceleration
(-1 the input)."""

Follower = tuple[str, tuple[str, ...]]
"""A cam pair's name and its follower's columns: displacement, velocity, acceleration (those there are)."""


class Column(NamedTuple):
    """One reported quantity at every row; ``values`` hold 0.0 where ``valid`` is False (a named tuple:
    frozen, and cheap to make, for a sweep makes one per quantity per call)."""

    name: str
    kind: Kind
    values: Reals
    valid: Bools

    @property
    def order(self) -> int:
        """The order of the transmission function it belongs to: 0 position, 1 velocity, 2 acceleration."""
        return ORDER[self.kind]


class SweepResult(Struct, frozen=True, dict=True):
    """A sweep: the input column, the asked columns, each row's status and warnings."""

    scene: Scene
    input: Column
    columns: tuple[Column, ...]
    status: npt.NDArray[np.int8]
    warnings: dict[int, str]
    notices: tuple[Notice, ...]
    periodic: bool
    seed_value: float
    seed_row: int = 0
    """The row computed at the scene's own input (among all rows computed, shown or not)."""
    timing: dict[str, float] = field(default_factory=dict)
    """Seconds spent: preparing, finding the range, executing, in all (filled by ``run_sweep`` when done)."""
    positions: Positions | None = None
    """The link poses at every row computed (shown or not), read by ``kinepoly.sweep.rows``."""
    shown: Bools | None = None
    """Which of the rows computed are shown (the rows of ``input`` and ``columns``)."""
    followers: tuple[Follower, ...] = ()
    """Each cam pair's follower columns (displacement, velocity, acceleration): its s-v-a diagram."""

    @cached_property
    def skeleton(self) -> tuple[tuple[str, tuple[complex, ...]], ...]:
        """Each solved link's points at the scene's own input (frame coordinates), for drawings."""
        if self.positions is None:
            return ()
        return tuple((link, tuple(complex(*pose.world(p.local)) for p in self.scene.link(link).points))
                     for link, pose in self.positions.row(self.seed_row).items())

    def column(self, name: str) -> Column:
        for col in (self.input, *self.columns):
            if col.name == name:
                return col
        raise KeyError(name)

    @property
    def rows(self) -> int:
        return len(self.input.values)

    def status_name(self, row: int) -> str:
        return STATUS[int(self.status[row])]
