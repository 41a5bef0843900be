"""The error over the input's range (a full turn, a rocker's swing, a slider's stroke), singular positions marked.

The rows are the project's sweep's (``kinepoly.sweep``): its range (a full turn when the input
link turns all the way round, else the stretch about the scene's own input where the mechanism
closes, to its ends), the assembly it follows from the scene's own input, and each row's status
(ok, near-singular, singular, cannot-assemble). At every row that is ok or near-singular the
methods are measured against the 50-digit reference: the construction is ``solve`` at that input
with a ``[guess]`` of every point where the sweep put it (``kinepoly.sweep.rows``), so it stays in
the sweep's assembly, and the other methods that solve a position start from the same guess.

The singular positions marked are the ends of a range where the mechanism stops closing (dead
centres, found by the sweep) and the rows the sweep finds singular.
"""

from __future__ import annotations

import math
from typing import Any, Literal, cast

import numpy as np
from msgspec import Struct

from kinepoly.bench.methods import Guess, Method, Setting, construction_values, methods_for, with_input
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import bench_keys, kind_errors
from kinepoly.errors import KinepolyError
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import LinkInput, SliderInput
from kinepoly.solution import Solution, solve
from kinepoly.sweep import SweepResult, prepare_sweep
from kinepoly.sweep import run_sweep as sweep_rows
from kinepoly.sweep.rows import row_guesses

__all__ = ["SWEEP_FD_STEP", "Sweep", "SweepPoint", "run_sweep", "solve_at"]

SWEEP_FD_STEP = 1e-4
"""The finite-difference step shown in a sweep (about the best for accelerations: u^(1/4))."""

Status = Literal["ok", "near-singular", "singular", "cannot-assemble"]
MEASURED: tuple[Status, ...] = ("ok", "near-singular")
"""The statuses of the rows where the methods are measured (the sweep has velocities there)."""


class SweepPoint(Struct, frozen=True):
    """One input of the sweep: the sweep's status, each method's error, the construction's estimate."""

    t: float
    status: Status
    errors: dict[str, float]
    estimate: float | None = None
    condition: float | None = None
    message: str = ""

    @property
    def measured(self) -> bool:
        return self.status in MEASURED and bool(self.errors)


class Sweep(Struct, frozen=True):
    """The sweep: inputs in order, the methods shown, and the singular positions found."""

    title: str
    input_name: str
    input_unit: str
    display_factor: float
    points: tuple[SweepPoint, ...]
    methods: tuple[str, ...]
    singular: tuple[float, ...]

    def shown(self, t: float) -> float:
        """An input as the user reads it (degrees where the scene uses them)."""
        return t * self.display_factor


def _inputs(result: SweepResult, factor: float) -> np.ndarray:
    """The sweep's inputs in radians (or lengths)."""
    values = np.asarray(result.input.values, np.float64)
    return np.radians(values) if factor != 1.0 else values


def _shifted(guess: Guess | None, origin: tuple[float, float]) -> Guess | None:
    """A guess in the scene's frame, in the solve's own frame (where the methods run)."""
    if guess is None or origin == (0.0, 0.0):
        return guess
    return tuple((name, (x - origin[0], y - origin[1])) for name, (x, y) in guess)


def solve_at(solution: Solution, t: float, guess: Guess | None) -> Solution:
    """``solution``'s scene solved at input ``t`` (radians or length), in the assembly ``guess`` pins (a row's
    guess from ``kinepoly.sweep.rows``: the sweep's assembly)."""
    return solve(with_input(solution.mechanism, t, guess).scene)


def _singular(result: SweepResult, ts: np.ndarray) -> list[float]:
    """The rows the sweep finds singular, and the ends of a range where the mechanism stops closing.

    A range that is not a full turn ends where the mechanism stops closing, unless the sweep says
    it stopped short (``open-range``: a slider still closing ten times the mechanism's size away);
    then only an end the sweep finds near-singular or worse counts.
    """
    rows = [n for n in range(result.rows) if result.status_name(n) == "singular"]
    if not result.periodic and result.rows:
        stopped_short = any(notice.code == "open-range" for notice in result.notices)
        rows += [end for end in dict.fromkeys((0, result.rows - 1))
                 if end not in rows and (not stopped_short or result.status_name(end) != "ok")]
    return [float(ts[n]) for n in rows]


def _analytic_values(sol: Solution, keys: tuple[str, ...], origin: tuple[float, float]) -> dict[str, Any]:
    out = {}
    for q in sol.check.quantities:
        if q.key in keys:
            value = q.analytic
            if q.kind == "position" and isinstance(value, tuple) and q.key.startswith("points."):
                value = (value[0] + origin[0], value[1] + origin[1])
            out[q.key] = value
    return out


def run_sweep(solution: Solution, count: int = 120) -> Sweep:
    """The error of each method at ``count`` inputs over the input's range (see the module's text)."""
    keys = bench_keys(solution)
    setting = Setting(solution, keys)
    mech, origin = setting.mechanism, setting.origin
    name, unit, factor = _input_axis(mech)
    result = sweep_rows(prepare_sweep(solution.scene), steps=count)
    ts = _inputs(result, factor)
    guesses = row_guesses(result)
    statuses = [cast(Status, result.status_name(n)) for n in range(result.rows)]
    shown = [m for m in methods_for(setting, (SWEEP_FD_STEP,)) if m.family not in ("construction", "analytic")]
    good = [n for n, status in enumerate(statuses) if status in MEASURED and guesses[n] is not None]
    batched = {m.name: m.compute(ts[good], None) for m in shown if m.batched}
    names = ["construction (polygons, homogeneous crossings)", "analytic Jacobian solve"] + [m.name for m in shown]
    points: list[SweepPoint] = []
    for n, t in enumerate(ts):
        status, message = statuses[n], result.warnings.get(n, "")
        if n not in good:
            points.append(SweepPoint(float(t), status, {}, message=message))
            continue
        try:
            got = solve_at(solution, float(t), guesses[n])
            assert got.inside is not None and got.accuracy is not None
            reference = reference_values(mech, got.inside.pose, list(keys), t=float(t), origin=origin)
        except KinepolyError as error:  # the sweep's arrays close here, the solve or the reference does not
            points.append(SweepPoint(float(t), status, {}, message="; ".join(filter(None, (message, str(error))))))
            continue
        scales = dict(got.check.scales)
        errors = {names[0]: _worst(kind_errors(construction_values(got, keys, origin), reference, scales)),
                  names[1]: _worst(kind_errors(_analytic_values(got, keys, origin), reference, scales))}
        for m in shown:
            try:
                values = _one(m, batched, good.index(n), float(t), _shifted(guesses[n], origin))
            except KinepolyError:  # a finite-difference step past a dead centre: no answer here
                errors[m.name] = math.nan
                continue
            errors[m.name] = _worst(kind_errors(values, reference, scales))
        points.append(SweepPoint(float(t), status, errors, got.accuracy.estimate.largest,
                                 got.check.condition_number, message))
    return Sweep(solution.scene.title, name, unit, factor, tuple(points), tuple(names),
                 tuple(sorted(_singular(result, ts))))


def _input_axis(mechanism: Mechanism) -> tuple[str, str, float]:
    """The input's textbook name, the unit it is shown in, and the factor from radians (or lengths)."""
    inp, units = mechanism.scene.input, mechanism.scene.units
    if isinstance(inp, LinkInput):
        return f"theta{mechanism.ground}{inp.link}", units.angle, 180.0 / math.pi if units.angle == "deg" else 1.0
    assert isinstance(inp, SliderInput)
    return f"s{inp.slider}", units.length, 1.0


def _one(method: Method, batched: dict[str, Any], index: int, t: float, guess: Guess | None) -> dict[str, Any]:
    if method.batched:
        return method.values(batched[method.name], index)
    return method.values(method.compute(np.array([t]), [guess] if guess else None), 0)


def _worst(errors: dict[str, float]) -> float:
    return max(errors.values(), default=math.nan)
