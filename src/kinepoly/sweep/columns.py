"""The columns of one sweep as its stages give them, their validity settled once every row's level is known."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from kinepoly.engine.position import Positions
from kinepoly.geom.arrays import Bools, Points, Reals
from kinepoly.model.mechanism import Mechanism
from kinepoly.sweep.result import NEAR_SINGULAR, ORDER, SINGULAR, Column, Kind

__all__ = ["ColumnBuilder"]


@dataclass
class ColumnBuilder:
    """Collects the columns of one sweep; their validity is settled once every row's level is known."""

    mechanism: Mechanism
    positions: Positions
    raw: list[tuple[str, Kind, Reals, Bools | None]] = field(default_factory=list)
    sources: list[tuple[Kind, Reals | Points]] = field(default_factory=list)
    """What each column (or pair of columns) was read from, once: the arrays whose sums tell overflow."""

    def add(self, name: str, kind: Kind, values: Reals, extra: Bools | None = None) -> None:
        self.raw.append((name, kind, values, extra))
        self.sources.append((kind, values))

    def pair(self, name: str, kind: Kind, values: Points, extra: Bools | None = None) -> None:
        self.raw += [(f"{name}_x", kind, values.real, extra), (f"{name}_y", kind, values.imag, extra)]
        self.sources.append((kind, values))

    def columns(self, level: npt.NDArray[np.int8] | None, shown: Bools, every: bool) -> tuple[Column, ...]:
        """The columns of the ``shown`` rows (``every``: all of them); ``level`` None where every row is ok."""
        if level is None:
            everywhere = (np.ones(len(shown) if every else int(shown.sum()), np.bool_), True)
            masks = {SINGULAR: everywhere, NEAR_SINGULAR: everywhere}
        else:
            masks = {}
            for limit in (SINGULAR, NEAR_SINGULAR):
                valid = level <= limit
                masks[limit] = (valid if every else valid[shown], bool(valid.all()))
        out = []
        for name, kind, values, extra in self.raw:
            valid, clean = masks[SINGULAR if ORDER[kind] <= 0 else NEAR_SINGULAR]
            values = values if every else values[shown]
            if extra is not None:
                valid = valid & (extra if every else extra[shown])
                clean = bool(valid.all())
            if not clean:
                values = np.where(valid, values, 0.0)
            out.append(Column(name, kind, np.asarray(values, np.float64), valid))
        return tuple(out)
