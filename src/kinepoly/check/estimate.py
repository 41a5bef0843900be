"""Error estimates from the conditioning, and the two ways of measuring an error.

The estimates are relative to the size of each kind of quantity in the scene (the same
normwise scale the cross-check uses), u = 2^-53 the unit roundoff and k the 2-norm condition
number of the dimensionless velocity equations (``AnalyticSolution.condition_number``):

* a crossing of two direction lines at an angle eps:      C_CROSSING u / |sin eps|
* positions and angles (the position's own conditioning):  C_POSITION u k
* velocities and omegas:                                  C_VELOCITY u k^2
* accelerations and alphas:                               C_ACCELERATION u k^2

k enters squared because the position itself has a square-root singularity at a dead point:
a position error of u k tilts the direction lines, and the tilted lines cross with a gain of k
again. A polygon's estimate is the larger of its k term and its worst crossing.

The constants are calibrated (``benchmarks/calibrate_estimates.py``) on 1000 random mechanisms
of every standard kind (``kinepoly.bench.cases``), from ordinary poses to 1e-8 rad short of a
dead point, against a 50-digit reference and against the analytic check: the largest ratio of
error to u k was 1.6 for positions, to u k^2 0.25 for velocities and 0.75 for accelerations
(99th percentiles 1.2, 0.15, 0.49). The constants leave a margin of 2 to 2.5 over the largest,
so the estimate bounds the error in at least 99% of random cases; it overstates it by about
50 at ordinary poses and by k / 100 or so near a dead point (where the cross-check's difference
understates it: both solutions start from the same rounded position).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

from msgspec import Struct

from kinepoly.engine.steps import Step
from kinepoly.geom.lines import intersect
from kinepoly.geom.tolerances import TINY_POSITIVE, UNIT_ROUNDOFF
from kinepoly.geom.vec import norm

__all__ = [
    "C_ACCELERATION",
    "C_CROSSING",
    "C_POSITION",
    "C_VELOCITY",
    "Crossing",
    "ErrorEstimate",
    "Value",
    "componentwise_error",
    "crossings",
    "estimate_errors",
    "normwise_error",
    "polygon_estimate",
]

C_CROSSING = 4.0
"""Constant of the per-crossing term u / |sin eps|."""

C_POSITION = 4.0
"""Constant of the position term u k (largest observed ratio 1.6)."""

C_VELOCITY = 0.5
"""Constant of the velocity term u k^2 (largest observed ratio 0.25)."""

C_ACCELERATION = 1.5
"""Constant of the acceleration term u k^2 (largest observed ratio 0.75)."""

_KIND_CLASS = {"position": "position", "angle": "position", "velocity": "velocity", "omega": "velocity",
               "instant_center": "velocity", "acceleration": "acceleration", "alpha": "acceleration"}
"""Which term bounds each kind; ``instant_center`` is an omega found from the instant centers."""


class Crossing(Struct, frozen=True):
    """One intersection step of a polygon: what it found and the sine of its lines' angle."""

    polygon: str
    result: str
    equation: str
    sin_angle: float

    @property
    def angle_deg(self) -> float:
        return math.degrees(math.asin(min(1.0, abs(self.sin_angle))))


def crossings(steps: Iterable[Step]) -> list[Crossing]:
    """Every step that crossed two direction lines (intersections and Mehmke images)."""
    out = []
    for step in steps:
        if step.kind not in ("intersection", "image") or len(step.lines) != 2:
            continue
        first, second = step.lines
        if norm(first.direction) == 0.0 or norm(second.direction) == 0.0:
            continue
        sin_angle = intersect(first, second).sin_angle  # the kernel's sine: unit directions first, no underflow
        out.append(Crossing(step.polygon, step.result, step.equation, sin_angle))
    return out


class ErrorEstimate(Struct, frozen=True):
    """The estimated normwise relative error of each kind, and what it was made of."""

    condition_number: float
    worst_crossing: dict[str, Crossing]
    relative: dict[str, float]

    @property
    def largest(self) -> float:
        return max(self.relative.values(), default=0.0)

    def of_kind(self, kind: str) -> float:
        return self.relative.get(kind, 0.0)


def _crossing_term(found: Crossing | None) -> float:
    return 0.0 if found is None else _sine_term(found.sin_angle)


def _sine_term(sin_angle: float) -> float:
    return C_CROSSING * UNIT_ROUNDOFF / max(abs(sin_angle), TINY_POSITIVE)


def _condition_term(polygon: str, k: float) -> float:
    """The k term of the velocities (``polygon`` "velocity") or of the accelerations."""
    return (C_VELOCITY if polygon == "velocity" else C_ACCELERATION) * UNIT_ROUNDOFF * k * k


def polygon_estimate(polygon: str, condition_number: float, sin_angle: float) -> float:
    """The estimate of one polygon's quantities (``polygon``: "velocity" or "acceleration") at a position whose
    velocity equations have ``condition_number`` and where a crossing of that polygon meets at ``sin_angle``: the
    larger of the two terms, as ``estimate_errors`` takes them (a sweep's row warns with it)."""
    k = max(condition_number, 1.0) if math.isfinite(condition_number) else math.inf
    return max(_condition_term(polygon, k), _sine_term(sin_angle))


def estimate_errors(condition_number: float, steps: Sequence[Step], kinds: Iterable[str],
                    floor: dict[str, float] | None = None) -> ErrorEstimate:
    """The estimate of every kind in ``kinds`` (position, angle, velocity, omega, acceleration, alpha,
    instant_center); ``floor`` raises a kind to an estimate made elsewhere (the Kennedy steps')."""
    k = max(condition_number, 1.0) if math.isfinite(condition_number) else math.inf
    u = UNIT_ROUNDOFF
    worst: dict[str, Crossing] = {}
    for found in crossings(steps):
        if found.polygon not in worst or abs(found.sin_angle) < abs(worst[found.polygon].sin_angle):
            worst[found.polygon] = found
    terms = {
        "position": C_POSITION * u * k,
        "velocity": max(_condition_term("velocity", k), _crossing_term(worst.get("velocity"))),
        "acceleration": max(_condition_term("acceleration", k), _crossing_term(worst.get("acceleration")),
                            _crossing_term(worst.get("velocity"))),
    }
    relative = {kind: max(terms[_KIND_CLASS[kind]], (floor or {}).get(kind, 0.0))
                for kind in sorted(set(kinds)) if kind in _KIND_CLASS}
    return ErrorEstimate(condition_number, worst, relative)


Value = float | tuple[float, float]
"""A scalar or a 2D vector quantity."""


def normwise_error(got: Value, reference: Value, scale: float) -> float:
    """|got - reference| / scale: the error against the size of its kind in the scene."""
    if isinstance(got, tuple) and isinstance(reference, tuple):
        diff = math.hypot(got[0] - reference[0], got[1] - reference[1])
    else:
        assert isinstance(got, float) and isinstance(reference, float)
        diff = abs(got - reference)
    return diff / scale if scale > 0.0 else diff


def componentwise_error(got: Value, reference: Value) -> float | None:
    """max_i |got_i - reference_i| / |reference_i|; None where a component of the reference is 0
    and the values differ (the ratio is infinite: the measure fails, not the method)."""
    pairs = list(zip(got, reference, strict=True)) if isinstance(got, tuple) and isinstance(reference, tuple) \
        else [(float(got), float(reference))]  # type: ignore[arg-type]
    worst = 0.0
    for g, r in pairs:
        diff = abs(g - r)
        if diff == 0.0:
            continue
        if r == 0.0:
            return None
        worst = max(worst, diff / abs(r))
    return worst
