"""Every reported quantity with its two values, their difference and its error estimate.

Two relative errors are given per quantity, and per kind the worst of each:

* normwise: |construction - analytic| over the size of that kind in the whole scene (the
  cross-check's measure; it stays meaningful when the quantity itself passes through zero);
* componentwise: max_i |construction_i - analytic_i| / |analytic_i|, which grows without
  bound as a component nears zero (a slider at its dead centre, a Coriolis term at a slide
  reversal) although nothing is wrong there. It is ``None`` where a component is exactly zero
  and the values differ.
"""

from __future__ import annotations

from msgspec import Struct

from kinepoly.check.compare import CheckReport, Quantity
from kinepoly.check.estimate import ErrorEstimate, Value, componentwise_error
from kinepoly.check.frame import LocalFrame

__all__ = ["AccuracyReport", "QuantityError", "assess"]


class QuantityError(Struct, frozen=True):
    """One quantity: both values (positions in the user's frame), difference, estimate, relative errors."""

    key: str
    kind: str
    construction: Value
    analytic: Value
    difference: float
    estimate: float
    normwise: float
    componentwise: float | None


class AccuracyReport(Struct, frozen=True):
    """Per-quantity errors, per-kind normwise, componentwise and estimated relative errors."""

    quantities: tuple[QuantityError, ...]
    normwise: dict[str, float]
    componentwise: dict[str, float | None]
    estimate: ErrorEstimate

    @property
    def estimated(self) -> dict[str, float]:
        return dict(self.estimate.relative)


def _user_value(q: Quantity, value: Value, frame: LocalFrame) -> Value:
    if q.kind == "position" and isinstance(value, tuple) and q.key.startswith("points."):
        return frame.to_user(value)
    return value


def _componentwise(q: Quantity) -> float | None:
    if isinstance(q.analytic, tuple):
        return componentwise_error(q.construction, q.analytic)
    if q.difference == 0.0:
        return 0.0
    return q.difference / abs(q.analytic) if q.analytic != 0.0 else None


def _worst(values: list[float | None]) -> float | None:
    if any(v is None for v in values):
        return None
    return max((v for v in values if v is not None), default=0.0)


def assess(check: CheckReport, estimate: ErrorEstimate, frame: LocalFrame) -> AccuracyReport:
    """The report of every quantity the check compared (differences taken in the solve's own frame)."""
    rows = []
    for q in check.quantities:
        scale = check.scales[q.kind]
        rows.append(QuantityError(
            key=q.key, kind=q.kind,
            construction=_user_value(q, q.construction, frame), analytic=_user_value(q, q.analytic, frame),
            difference=q.difference, estimate=estimate.of_kind(q.kind) * scale,
            normwise=q.difference / scale, componentwise=_componentwise(q),
        ))
    kinds = sorted({r.kind for r in rows})
    normwise = {k: max(r.normwise for r in rows if r.kind == k) for k in kinds}
    componentwise = {k: _worst([r.componentwise for r in rows if r.kind == k]) for k in kinds}
    return AccuracyReport(tuple(rows), normwise, componentwise, estimate)
