"""The cross-check: every reported quantity against the independent analytic solution.

Errors are normwise per kind of quantity: |construction - analytic| over the largest
magnitude of that kind in the scene (angles: absolute, in radians). "In the scene" counts
every value the solution knows, not only the asked ones, and the natural size each kind takes
from the others (alpha from omega^2, velocity from L omega, acceleration from L omega^2 and
L alpha), so that a kind that is zero at this instant (every alpha of a parallelogram linkage
at constant speed) is not measured against round-off.
"""

from __future__ import annotations

import math

from msgspec import Struct

__all__ = ["CheckReport", "Quantity", "compare"]

Value = float | tuple[float, float]


class Quantity(Struct, frozen=True):
    """One reported quantity: its key (``points.C.velocity``), kind, and both values."""

    key: str
    kind: str
    construction: Value
    analytic: Value

    @property
    def difference(self) -> float:
        if isinstance(self.construction, tuple) and isinstance(self.analytic, tuple):
            return math.hypot(self.construction[0] - self.analytic[0], self.construction[1] - self.analytic[1])
        assert isinstance(self.construction, float) and isinstance(self.analytic, float)
        diff = self.construction - self.analytic
        if self.kind == "angle":
            diff = math.remainder(diff, 2.0 * math.pi)
        return abs(diff)

    @property
    def magnitude(self) -> float:
        if isinstance(self.analytic, tuple):
            return math.hypot(*self.analytic)
        return abs(self.analytic)


class CheckReport(Struct, frozen=True):
    """Per-quantity differences and the normwise relative error of each kind, and the worst."""

    quantities: tuple[Quantity, ...]
    relative: dict[str, float]
    condition_number: float
    scales: dict[str, float]

    @property
    def max_rel_error(self) -> float:
        return max(self.relative.values(), default=0.0)

    def relative_error(self, quantity: Quantity) -> float:
        return quantity.difference / self.scales[quantity.kind]


def _scale(quantities: tuple[Quantity, ...], kind: str, natural: dict[str, float]) -> float:
    if kind == "angle":
        return 1.0
    largest = max([q.magnitude for q in quantities if q.kind == kind] + [natural.get(kind, 0.0)])
    return largest if largest > 0.0 else 1.0


def compare(quantities: list[Quantity], condition_number: float,
            natural: dict[str, float] | None = None) -> CheckReport:
    """The report; ``natural`` gives each kind's size in the scene beyond the asked quantities."""
    kinds = sorted({q.kind for q in quantities})
    frozen = tuple(quantities)
    scales = {k: _scale(frozen, k, natural or {}) for k in kinds}
    relative = {k: max(q.difference for q in frozen if q.kind == k) / scales[k] for k in kinds}
    return CheckReport(frozen, relative, condition_number, scales)
