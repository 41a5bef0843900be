"""The columns of one sweep as its stages give them, their validity settled once every row's level is known."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
import numpy.typing as npt
from msgspec import Struct, field

from kinepoly.engine.position import Positions
from kinepoly.geom.arrays import Bools, Points, Reals, trues
from kinepoly.model.mechanism import Mechanism
from kinepoly.sweep.result import NEAR_SINGULAR, ORDER, SINGULAR, Column, Kind

__all__ = ["ColumnBuilder", "Raw"]

_FLOAT = np.dtype(np.float64)
"""The dtype of doubles: numpy's one instance of it, which a column's values already have unless a stage gave others."""


def _doubles(values: Reals) -> Reals:
    """``np.asarray(values, np.float64)``: the values themselves where they are doubles already (most are), without
    numpy's call."""
    return values if values.dtype is _FLOAT else np.asarray(values, np.float64)


Raw = tuple[str, Kind, Reals, Bools | None]
"""A column as a stage gives it: its name, kind, values at every row, and the rows where it has a value besides
those the row's level allows (None: all of them)."""


class ColumnBuilder(Struct):
    """Collects the columns of one sweep; their validity is settled once every row's level is known."""

    mechanism: Mechanism
    positions: Positions
    raw: list[Raw] = field(default_factory=list)
    top: int = -1
    """The highest order of the columns added (``ORDER``)."""
    tops: list[Reals | Points] = field(default_factory=list)
    """What the columns of the highest order were read from, each once: the arrays whose sums tell overflow."""
    extra: bool = False
    """Whether a column has rows of its own without a value (``Raw``)."""

    def add(self, name: str, kind: Kind, values: Reals, extra: Bools | None = None) -> None:
        self.extend(((name, kind, values, extra),), ((kind, values),))

    def pair(self, name: str, kind: Kind, values: Points, extra: Bools | None = None) -> None:
        """A point's two columns, ``<name>_x`` and ``<name>_y``."""
        self.extend(((f"{name}_x", kind, values.real, extra), (f"{name}_y", kind, values.imag, extra)),
                    ((kind, values),))

    def extend(self, raw: Sequence[Raw], sources: Iterable[tuple[Kind, Reals | Points]]) -> None:
        """Columns, and what they were read from (each array once: a point's, for its two columns)."""
        self.raw += raw
        self.extra = self.extra or any(rows is not None for _, _, _, rows in raw)
        for kind, values in sources:
            order = ORDER[kind]
            if order > self.top:
                self.top, self.tops = order, [values]
            elif order == self.top:
                self.tops += (values,)

    def columns(self, level: npt.NDArray[np.int8] | None, shown: Bools, every: bool) -> tuple[Column, ...]:
        """The columns of the ``shown`` rows (``every``: all of them); ``level`` None where every row is ok."""
        if level is None:
            plain = self._plain(shown, every)
            if plain is not None:
                return plain
            everywhere = (trues(len(shown) if every else np.count_nonzero(shown)), True)
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
            out.append(Column(name, kind, _doubles(values), valid))
        return tuple(out)

    def _plain(self, shown: Bools, every: bool) -> tuple[Column, ...] | None:
        """The columns where every row is ok and no column has rows of its own without a value: each column's shown
        values as they are (doubles: most are already), one mask for all (None where a column has such rows)."""
        if self.extra:
            return None
        everywhere = trues(len(shown) if every else np.count_nonzero(shown))
        return tuple([Column(name, kind, _doubles(values if every else values[shown]), everywhere)
                      for name, kind, values, _ in self.raw])
