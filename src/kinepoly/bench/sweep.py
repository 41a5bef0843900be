"""The error over a full turn of the input (a full stroke for a slider input), singular positions marked.

The sweep follows one assembly: each position's ``[guess]`` is every point extrapolated from
the two positions before it, so a linkage does not jump to its other assembly where the
scene's own guess would stop telling them apart (a parallelogram stays a parallelogram).
A position that cannot be assembled or is singular is recorded, not skipped silently; a
singular position between two samples is found where the determinant of the position
equations (from the reference) changes sign, and where assembly ends by bisection.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Literal

import numpy as np

from kinepoly.bench.methods import Guess, Method, Setting, construction_values, methods_for, with_input
from kinepoly.bench.reference import input_rates, reference_values
from kinepoly.bench.run import kind_errors
from kinepoly.errors import AssemblyError, KinepolyError, SingularityError
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import LinkInput, SliderInput
from kinepoly.solution import Solution, solve
from kinepoly.model.pose import Pose
from kinepoly.solve.position import solve_position

__all__ = ["SWEEP_FD_STEP", "Sweep", "SweepPoint", "run_sweep", "sweep_inputs"]

SWEEP_FD_STEP = 1e-4
"""The finite-difference step shown in a sweep (about the best for accelerations: u^(1/4))."""

Status = Literal["ok", "singular", "cannot-assemble"]


@dataclass(frozen=True)
class SweepPoint:
    """One input of the sweep: what happened, each method's error, the construction's estimate."""

    t: float
    status: Status
    errors: dict[str, float]
    estimate: float | None = None
    condition: float | None = None
    message: str = ""


@dataclass(frozen=True)
class Sweep:
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


def _assembles(mechanism: Mechanism, plan: Any, t: float, guess: Guess | None) -> bool:
    try:
        solve_position(with_input(mechanism, t, guess), plan)
    except (AssemblyError, SingularityError):
        return False
    return True


def _edge(mechanism: Mechanism, plan: Any, good: float, bad: float, guess: Guess | None) -> float:
    """Where assembly ends between a good and a bad input (bisection)."""
    for _ in range(60):
        mid = 0.5 * (good + bad)
        if mid in (good, bad):
            break
        if _assembles(mechanism, plan, mid, guess):
            good = mid
        else:
            bad = mid
    return 0.5 * (good + bad)


def sweep_inputs(setting: Setting, count: int) -> tuple[np.ndarray, tuple[float, ...]]:
    """The inputs of the sweep in increasing order, and the ends of a slider's stroke (its dead centres).

    A turning input runs over [0, 2 pi) through the scene's own angle; a slider over its stroke.
    """
    mech, plan = setting.mechanism, setting.solution.plan
    t0 = input_rates(mech)[0]
    if isinstance(mech.scene.input, LinkInput):
        turn = np.mod(t0 + 2.0 * math.pi * np.arange(count) / count, 2.0 * math.pi)
        return np.sort(np.where(turn > 2.0 * math.pi - 1e-12, 0.0, turn)), ()
    span = 2.0 * setting.input_unit
    probe = t0 + span * np.linspace(-1.0, 1.0, 8 * count + 1)
    ok = [_assembles(mech, plan, float(t), None) for t in probe]
    mid = int(np.argmin(np.abs(probe - t0)))
    lo, hi = mid, mid
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    while hi < len(probe) - 1 and ok[hi + 1]:
        hi += 1
    s_lo = _edge(mech, plan, float(probe[lo]), float(probe[lo - 1]), None) if lo > 0 else float(probe[0])
    s_hi = _edge(mech, plan, float(probe[hi]), float(probe[hi + 1]), None) if hi < len(probe) - 1 else float(probe[-1])
    half, centre = 0.5 * (s_hi - s_lo), 0.5 * (s_hi + s_lo)
    ts = centre - half * np.cos(math.pi * (np.arange(count) + 0.5) / count)  # dense toward the dead centres
    ends = tuple(x for x, inner in ((s_lo, lo > 0), (s_hi, hi < len(probe) - 1)) if inner)
    return ts, ends


def _guess_from(mechanism: Mechanism, poses: list[tuple[float, Pose]], t: float) -> Guess | None:
    """Every point of every link, extrapolated linearly from the last two poses to ``t``."""
    if not poses:
        return None
    (t1, p1) = poses[-1]
    spec = mechanism.scene
    out = []
    seen: set[str] = set()
    for link in spec.links:
        if link.name not in p1.links:
            continue
        for point in link.points:
            if point.name in seen:
                continue
            seen.add(point.name)
            at = p1.links[link.name].world(point.local)
            if len(poses) >= 2 and poses[-2][0] != t1:
                t0, p0 = poses[-2]
                before = p0.links[link.name].world(point.local)
                f = (t - t1) / (t1 - t0)
                at = (at[0] + f * (at[0] - before[0]), at[1] + f * (at[1] - before[1]))
            out.append((point.name, at))
    return tuple(out)


def _solve_at(setting: Setting, t: float, guess: Guess | None) -> Solution:
    scene = setting.mechanism.scene
    return solve(replace(scene, input=with_input(setting.mechanism, t).scene.input,
                         guess=scene.guess if guess is None else guess))


def _follow(setting: Setting, ts: np.ndarray) -> tuple[list[Guess | None], list[Solution | Exception]]:
    """Solve every input in turn, from the scene's own input outward, each guessed from its neighbours."""
    t_now = input_rates(setting.mechanism)[0]
    gap = ts - t_now
    if isinstance(setting.mechanism.scene.input, LinkInput):
        gap = np.remainder(gap + math.pi, 2.0 * math.pi) - math.pi
    start = int(np.argmin(np.abs(gap)))
    guesses: list[Guess | None] = [None] * len(ts)
    found: list[Solution | Exception] = [AssemblyError("not reached")] * len(ts)
    for order in (range(start, len(ts)), range(start - 1, -1, -1)):
        trail: list[tuple[float, Pose]] = []
        if order.start != start and isinstance(found[start], Solution):
            first = found[start]
            assert isinstance(first, Solution) and first.inside is not None
            trail = [(float(ts[start]), first.inside.pose)]
        for n in order:
            t = float(ts[n])
            guesses[n] = _guess_from(setting.mechanism, trail, t) if trail else None
            try:
                sol = _solve_at(setting, t, guesses[n])
            except (AssemblyError, SingularityError) as error:
                found[n] = error
                continue
            found[n] = sol
            assert sol.inside is not None
            trail = (trail + [(t, sol.inside.pose)])[-2:]
    return guesses, found


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
    """The error of each method at ``count`` inputs over a full turn (or the stroke) of the input."""
    keys = tuple(q.key for q in solution.check.quantities)
    setting = Setting(solution, keys)
    mech = setting.mechanism
    ts, ends = sweep_inputs(setting, count)
    guesses, found = _follow(setting, ts)
    shown = [m for m in methods_for(setting, (SWEEP_FD_STEP,)) if m.family not in ("construction", "analytic")]
    good = [n for n, f in enumerate(found) if isinstance(f, Solution)]
    batched = {m.name: m.compute(ts[good], None) for m in shown if m.batched}
    names = ["construction (polygons, homogeneous crossings)", "analytic Jacobian solve"] + [m.name for m in shown]
    points: list[SweepPoint] = []
    determinants: dict[int, Any] = {}
    for n, t in enumerate(ts):
        got = found[n]
        if not isinstance(got, Solution):
            status: Status = "singular" if isinstance(got, SingularityError) else "cannot-assemble"
            points.append(SweepPoint(float(t), status, {}, message=str(got)))
            continue
        assert got.inside is not None and got.accuracy is not None
        try:
            reference = reference_values(mech, got.inside.pose, list(keys), t=float(t), origin=setting.origin)
        except SingularityError as error:
            points.append(SweepPoint(float(t), "singular", {}, message=str(error)))
            continue
        determinants[n] = reference.determinant
        scales = dict(got.check.scales)
        errors = {names[0]: _worst(kind_errors(construction_values(got, keys, setting.origin), reference, scales)),
                  names[1]: _worst(kind_errors(_analytic_values(got, keys, setting.origin), reference, scales))}
        for m in shown:
            try:
                values = _one(m, batched, good.index(n), float(t), guesses[n])
            except KinepolyError:  # a finite-difference step past a dead centre: no answer here
                errors[m.name] = math.nan
                continue
            errors[m.name] = _worst(kind_errors(values, reference, scales))
        points.append(SweepPoint(float(t), "ok", errors, got.accuracy.estimate.largest,
                                 got.check.condition_number))
    singular = list(ends) + _sign_changes(ts, determinants) + _folds(setting, ts, found, guesses)
    name, unit, factor = _input_axis(mech)
    return Sweep(solution.scene.title, name, unit, factor, tuple(points), tuple(names), tuple(sorted(singular)))


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


def _sign_changes(ts: np.ndarray, dets: dict[int, Any]) -> list[float]:
    """Inputs between neighbouring samples where det Phi_q changes sign (by the secant)."""
    out = []
    for n in range(len(ts) - 1):
        if n in dets and n + 1 in dets and (dets[n] > 0) != (dets[n + 1] > 0):
            a, b = float(dets[n]), float(dets[n + 1])
            out.append(float(ts[n] + (ts[n + 1] - ts[n]) * a / (a - b)))
    return out


def _folds(setting: Setting, ts: np.ndarray, found: list[Any], guesses: list[Guess | None]) -> list[float]:
    """Where assembly ends between a solved sample and one that cannot be assembled."""
    out = []
    for n in range(len(ts) - 1):
        pair = (found[n], found[n + 1])
        if isinstance(pair[0], Solution) and isinstance(pair[1], AssemblyError):
            out.append(_edge(setting.mechanism, setting.solution.plan, float(ts[n]), float(ts[n + 1]), guesses[n]))
        elif isinstance(pair[1], Solution) and isinstance(pair[0], AssemblyError):
            out.append(_edge(setting.mechanism, setting.solution.plan, float(ts[n + 1]), float(ts[n]),
                             guesses[n + 1]))
    return out
