"""Run the bench: every method's error against the 50-digit reference, and its time per position.

Errors are normwise, as the cross-check measures them: for each kind of quantity the largest
|method - reference| over the size of that kind in the scene (angles: absolute radians), and
the method's error is the worst kind. Times are the median of repeats of one call (a whole
batch of positions for the numpy methods), divided by the positions in the call.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from msgspec import Struct

from kinepoly.bench.methods import Method, Setting, methods_for
from kinepoly.bench.motion import quantity_kind
from kinepoly.bench.reference import REFERENCE_DIGITS, Reference, input_rates, reference_values
from kinepoly.errors import KinepolyError
from kinepoly.solution import Solution

__all__ = ["BATCH", "BenchResult", "MethodResult", "bench_keys", "kind_errors", "run_bench", "time_per_position"]

BATCH = 256
"""Positions per call for the methods that run over a batch."""


class MethodResult(Struct, frozen=True):
    """One method: its error (normwise relative, worst kind), per-kind errors, time per position."""

    name: str
    family: str
    error: float
    errors: dict[str, float]
    time_s: float
    batch: int
    repeats: int
    quantities: int
    step: float | None = None
    failure: str = ""
    """Why the method gave no answer at this input (then error and time are NaN)."""


class BenchResult(Struct, frozen=True):
    title: str
    where: str
    methods: tuple[MethodResult, ...]
    reference_s: float
    estimate: float | None = None
    """The construction's error estimate at this input (relative, the worst kind)."""
    reference_digits: int = REFERENCE_DIGITS

    def method(self, family: str) -> MethodResult:
        return next(m for m in self.methods if m.family == family)


def time_per_position(call: Callable[[], Any], positions: int, *, min_repeats: int = 5, budget_s: float = 0.25,
                      max_repeats: int = 1000) -> tuple[float, int]:
    """(median seconds per position, repeats) of ``call``, which handles ``positions`` inputs."""
    call()  # warm up: imports, caches
    samples: list[float] = []
    spent = 0.0
    while len(samples) < min_repeats or (spent < budget_s and len(samples) < max_repeats):
        t0 = time.perf_counter()
        call()
        dt = time.perf_counter() - t0
        samples.append(dt)
        spent += dt
    return statistics.median(samples) / positions, len(samples)


def _difference(mp: Any, got: Any, ref: Any, kind: str) -> Any:
    if isinstance(ref, tuple):
        return mp.sqrt((mp.mpf(float(got[0])) - ref[0]) ** 2 + (mp.mpf(float(got[1])) - ref[1]) ** 2)
    diff = mp.mpf(float(got)) - ref
    if kind == "angle":
        diff = diff - 2 * mp.pi * mp.nint(diff / (2 * mp.pi))
    return abs(diff)


def kind_errors(values: dict[str, Any], reference: Reference, scales: dict[str, float]) -> dict[str, float]:
    """Per kind: max |value - reference| over the kind's size (computed in mpmath)."""
    import mpmath  # type: ignore[import-untyped]

    mp = mpmath.mp
    out: dict[str, float] = {}
    with mp.workdps(REFERENCE_DIGITS):
        for key, got in values.items():
            kind = quantity_kind(key)
            scale = 1.0 if kind == "angle" else scales.get(kind, 1.0) or 1.0
            err = float(_difference(mp, got, reference.values[key], kind)) / scale
            out[kind] = max(out.get(kind, 0.0), err)
    return out


def _scales(solution: Solution) -> dict[str, float]:
    return dict(solution.check.scales)


def bench_keys(solution: Solution) -> tuple[str, ...]:
    """The quantities the bench measures: the cross-check's, but the instant centers' (no method here gives them)."""
    return tuple(q.key for q in solution.check.quantities if not q.key.startswith("instant_centers."))


def run_bench(solution: Solution, *, budget_s: float = 0.25, steps: tuple[float, ...] | None = None) -> BenchResult:
    """Every method at the scene's input: error against the reference and time per position."""
    from kinepoly.engine.position import describe_input

    keys = bench_keys(solution)
    setting = Setting(solution, keys)
    assert solution.inside is not None
    t0 = time.perf_counter()
    reference = reference_values(setting.mechanism, setting.pose, list(keys), origin=setting.origin)
    reference_s = time.perf_counter() - t0
    t_now = input_rates(setting.mechanism)[0]
    scales = _scales(solution)
    results = []
    chosen = methods_for(setting) if steps is None else methods_for(setting, steps)
    for method in chosen:
        results.append(_measure(method, t_now, reference, scales, budget_s))
    estimate = solution.accuracy.estimate.largest if solution.accuracy else None
    return BenchResult(solution.scene.title, describe_input(setting.mechanism), tuple(results), reference_s, estimate)


def _measure(method: Method, t_now: float, reference: Reference, scales: dict[str, float],
             budget_s: float) -> MethodResult:
    one = np.array([t_now])
    try:
        values = method.values(method.compute(one, None), 0)
    except KinepolyError as error:
        return MethodResult(method.name, method.family, math.nan, {}, math.nan, 1, 0, 0, method.step, str(error))
    errors = kind_errors(values, reference, scales)
    batch = np.full(BATCH, t_now) if method.batched else one
    time_s, repeats = time_per_position(lambda: method.compute(batch, None), len(batch), budget_s=budget_s)
    worst = max(errors.values(), default=math.nan)
    return MethodResult(method.name, method.family, worst, errors, time_s, len(batch), repeats, len(values),
                        method.step)
